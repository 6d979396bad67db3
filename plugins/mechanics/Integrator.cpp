#include "Integrator.h"
