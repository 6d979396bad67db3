#include "fascia/materials/IncompressibleNeoHookean.h"
// header-only component; this file keeps the one .h/.cpp pair per component layout
