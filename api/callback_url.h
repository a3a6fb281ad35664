#pragma once

#include <string>
#include <string_view>

// A job's callback URL (JobOptions::callback_url, api/options.h), taken apart.

namespace papernet {

/// A callback_url's parts.
struct CallbackUrl {
  std::string host;  ///< lower case; an IPv6 address without its brackets
  int port = 80;
  std::string target = "/";  ///< path and query
};

/// Splits http://HOST[:PORT][/PATH][?QUERY] (at most 2048 bytes, no user, no fragment).
/// \throw InvalidOptionException invalid_option_value naming callback_url.
CallbackUrl parse_callback_url(std::string_view url);

}  // namespace papernet
