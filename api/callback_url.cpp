// A job's callback URL (api/callback_url.h, `parse_callback_url`): checked when the options are
// read, so that one that can never be sent is refused before a job exists, and taken apart
// again by the webhook's sender at each attempt.
#include "api/callback_url.h"

#include <algorithm>
#include <charconv>
#include <string>
#include <string_view>

#include "core/ascii.h"
#include "core/errors.h"

namespace papernet {

CallbackUrl parse_callback_url(std::string_view url) {
  const std::string name = "callback_url";
  auto refuse = [&](const std::string& why) -> CallbackUrl {
    throw InvalidOptionException("invalid_option_value", name, "option 'callback_url': " + why);
  };
  constexpr std::string_view kScheme = "http://";
  if (url.size() > 2048) return refuse("longer than 2048 bytes");
  for (const char c : url)
    if (static_cast<unsigned char>(c) <= 0x20 || static_cast<unsigned char>(c) >= 0x7f)
      return refuse("has a space, a control character or a byte outside ASCII (percent-encode it)");
  if (ascii_lower(std::string(url.substr(0, 8))) == "https://")
    return refuse(
        "https is not supported (the service has no TLS client); use http:// to a "
        "receiver on a private network or behind a proxy you trust");
  if (ascii_lower(std::string(url.substr(0, kScheme.size()))) != kScheme)
    return refuse("is not an http:// URL");
  std::string_view rest = url.substr(kScheme.size());
  if (rest.find('#') != std::string_view::npos) return refuse("has a fragment (#)");
  const std::size_t end = std::min(rest.find('/'), rest.find('?'));
  std::string_view authority = rest.substr(0, end);
  CallbackUrl out;
  if (end != std::string_view::npos) {
    // A query alone is asked of the root: "/?a=1".
    out.target.clear();
    if (rest[end] == '?') out.target.push_back('/');
    out.target.append(rest.substr(end));
  }
  if (authority.find('@') != std::string_view::npos) return refuse("has a user name");
  std::string_view port;
  if (!authority.empty() && authority[0] == '[') {
    const std::size_t close = authority.find(']');
    if (close == std::string_view::npos) return refuse("has an unclosed [");
    out.host = std::string(authority.substr(1, close - 1));
    const std::string_view after = authority.substr(close + 1);
    if (!after.empty() && after[0] != ':') return refuse("has text after ]");
    if (!after.empty()) port = after.substr(1);
    if (out.host.empty() ||
        out.host.find_first_not_of("0123456789abcdefABCDEF:.") != std::string::npos)
      return refuse("has no IPv6 address between [ and ]");
  } else {
    const std::size_t colon = authority.find(':');
    out.host = std::string(authority.substr(0, colon));
    if (colon != std::string_view::npos) port = authority.substr(colon + 1);
    if (out.host.empty() || out.host.size() > 253 ||
        out.host.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                   ".-") != std::string::npos)
      return refuse("has no host name");
  }
  out.host = ascii_lower(out.host);
  if (authority.find(':') != std::string_view::npos && port.empty() && authority[0] != '[')
    return refuse("has an empty port");
  if (!port.empty()) {
    int p = 0;
    const auto [at, ec] = std::from_chars(port.data(), port.data() + port.size(), p);
    if (ec != std::errc() || at != port.data() + port.size() || p < 1 || p > 65535)
      return refuse("has a port that is not 1..65535");
    out.port = p;
  }
  return out;
}

}  // namespace papernet
