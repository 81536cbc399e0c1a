// Small helpers shared by the glTF loader and writer shims (C++ only, internal).
#ifndef SAARCOR_GLTF_UTIL_H
#define SAARCOR_GLTF_UTIL_H

#include <cctype>
#include <cstdio>
#include <cstring>
#include <string>

namespace gltf_util {

inline std::string first_line(const std::string &s)
{
    std::string l = s.substr(0, s.find('\n'));
    while (!l.empty() && (l.back() == '\r' || l.back() == ' '))
        l.pop_back();
    return l;
}

// Case-insensitive suffix test (".glb", ".gltf"); suffix must be lower case.
inline bool ends_with(const std::string &s, const char *suffix)
{
    const size_t n = std::strlen(suffix);
    if (s.size() < n)
        return false;
    for (size_t i = 0; i < n; i++)
        if (std::tolower((unsigned char)s[s.size() - n + i]) != suffix[i])
            return false;
    return true;
}

// Copies the first line of msg into the C caller's error buffer.
inline void set_error(char *err, size_t errlen, const std::string &msg)
{
    if (err && errlen)
        std::snprintf(err, errlen, "%s", first_line(msg).c_str());
}

} // namespace gltf_util

#endif
