// POST /v1/jobs as the service receives it: httplib reads the request (query string, headers,
// multipart/form-data parts) from an in-memory stream, then the route's own parse_upload turns it
// into a job with the service's limits (the route streams its body through a bounded reader;
// here upload_request_of takes the parts httplib buffered), and the job's mesh is loaded and
// validated as the worker would.
// Input: the query string, a newline, the Content-Type, a newline, the body (make_corpus.sh).
#include <httplib.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "api/options.h"
#include "fuzz/fuzz_pipeline.h"
#include "server/config.h"
#include "server/problem.h"
#include "server/upload.h"

namespace {

using namespace papernet;

class MemoryStream final : public httplib::Stream {
 public:
  explicit MemoryStream(std::string_view in) : in_(in) {}
  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const std::size_t n = std::min(size, in_.size());
    std::memcpy(ptr, in_.data(), n);
    in_.remove_prefix(n);
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char*, size_t size) override { return static_cast<ssize_t>(size); }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 40000;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 8080;
  }
  socket_t socket() const override { return INVALID_SOCKET; }

 private:
  std::string_view in_;
};

// httplib::Server with its request processing reachable without a socket.
class FuzzServer final : public httplib::Server {
 public:
  FuzzServer() {
    const server::ServerConfig config;
    OptionsLimits limits;
    limits.max_time_limit = config.max_job_time_limit;
    limits.max_target_faces = config.max_faces;
    set_payload_max_length(config.max_body_bytes);
    Post("/v1/jobs", [limits](const httplib::Request& req, httplib::Response& res) {
      try {
        server::ParsedUpload upload = server::parse_upload(server::upload_request_of(req), limits);
        fuzz::load_and_validate(upload.input.mesh, upload.input.format,
                                upload.input.external_files);
        res.status = 202;
      } catch (const server::ApiError&) {
        res.status = 400;
      } catch (const InvalidOptionException&) {
        res.status = 400;
      } catch (const std::exception& e) {
        // The service would answer 500: no input may get there.
        std::fprintf(stderr, "unexpected exception: %s\n", e.what());
        std::abort();
      }
    });
  }
  void process(std::string_view request) {
    MemoryStream stream(request);
    bool closed = false;
    process_request(stream, true, closed, [](httplib::Request&) {});
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static FuzzServer server;
  std::string_view input(reinterpret_cast<const char*>(data), size);
  auto line = [&input] {
    const std::size_t end = std::min(input.find('\n'), input.size());
    std::string out(input.substr(0, end));
    input.remove_prefix(std::min(input.size(), end + 1));
    out.erase(std::remove(out.begin(), out.end(), '\r'), out.end());
    return out;
  };
  const std::string query = line();
  const std::string content_type = line();
  std::string request = "POST /v1/jobs" + (query.empty() ? "" : "?" + query) +
                        " HTTP/1.1\r\nHost: localhost\r\nContent-Type: " + content_type +
                        "\r\nContent-Length: " + std::to_string(input.size()) + "\r\n\r\n";
  request.append(input);
  server.process(request);
  return 0;
}
