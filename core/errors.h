#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace papernet {

/// The input cannot be read: a missing file, a malformed or truncated stream, an unsupported
/// format, or a size over a configured limit.
class IOException : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input is over a configured size limit (bytes, faces, vertices), said before anything of
/// that size is allocated. A service answers it with "too large" rather than "unreadable".
class LimitExceededException : public IOException {
 public:
  enum class Limit { Bytes, Faces, Vertices, Pixels };
  LimitExceededException(Limit limit, const std::string& message)
      : IOException(message), limit_(limit) {}
  Limit limit() const { return limit_; }

 private:
  Limit limit_;
};

/// The input was read but is not a mesh we can unfold (non-manifold, degenerate, empty, ...).
/// The message names the fault.
class InvalidInputException : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A caller's option cannot be accepted: an unknown name, a malformed value, a value out of
/// range, or options that contradict each other. Not a fault of the mesh: a service answers it
/// with 400 naming the option. `code` is stable: unknown_option, invalid_option_value,
/// option_out_of_range, conflicting_options, malformed_options.
class InvalidOptionException : public std::invalid_argument {
 public:
  InvalidOptionException(std::string code, std::string option, const std::string& message)
      : std::invalid_argument(message), code_(std::move(code)), option_(std::move(option)) {}
  const std::string& code() const { return code_; }
  /// The offending option's name ("" when the whole set is at fault or the name is unknown).
  const std::string& option() const { return option_; }

 private:
  std::string code_;
  std::string option_;
};

/// An operation would break the mesh's connectivity (an illegal collapse, a broken tree).
class TopologyException : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// A long computation was stopped through its Progress hook.
class CancelledException : public std::runtime_error {
 public:
  CancelledException() : std::runtime_error("cancelled") {}
};

}  // namespace papernet
