#pragma once

#include <string>
#include <string_view>

namespace papernet {

/// `s` with its ASCII capitals in lower case, every other byte as it is: for names compared
/// without case (options' words, paper names, media types, extensions, hex digests), whatever
/// the locale.
inline std::string ascii_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

}  // namespace papernet
