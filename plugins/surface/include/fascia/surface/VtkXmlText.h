#pragma once
/// Two small readings of VTK XML files that the .vtp surface reader (plugins/surface) and the .vtu
/// mesh reader (plugins/meshio) both need before and after VTK parses a file: base64 data decoded
/// as VTK 9.1 decodes it, and the byte VTK's XML parser names in its messages. Header only, and no
/// VTK: a build without VTK compiles it too.
#include <charconv>
#include <string>

namespace fascia::surface {

/// Up to `want` bytes of the base64 text of `text` from `at` to `end`, ending at padding or at a
/// character that is not base64; spaces are skipped unless `strict` (VTK decodes its data 4
/// characters at a time, every one base64).
inline std::string decodeBase64(const std::string& text, size_t at, size_t end, size_t want, bool strict) {
    std::string out;
    unsigned buf = 0;
    int bits = 0;
    for (size_t p = at; p < end && out.size() < want; ++p) {
        const char c = text[p];
        const int v = c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52
                      : c == '+' ? 62 : c == '/' ? 63 : -1;
        if (v < 0) {
            if (!strict && (c == ' ' || c == '\n' || c == '\r' || c == '\t')) continue;
            break;  // padding, or the end of the data
        }
        buf = (buf << 6) | unsigned(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out += char((buf >> bits) & 0xFF);
        }
    }
    return out;
}

/// The byte VTK's XML parser names in its message ("... byte index N: ..."); -1 when none does.
inline long long vtkParserByte(const std::string& message) {
    const std::string key = "byte index ";
    const size_t p = message.find(key);
    if (p == std::string::npos) return -1;
    long long n = -1;
    const char* b = message.c_str() + p + key.size();
    const auto [end, ec] = std::from_chars(b, message.c_str() + message.size(), n);
    return ec == std::errc() && end != b && n >= 0 ? n : -1;
}

} // namespace fascia::surface
