// Hostile input over real HTTP: a real `papernet serve` on a loopback port, spoken to with raw
// sockets where a client library would be too polite (declared lengths it never sends, trickled
// headers, truncated bodies). Every case ends by checking that a normal job still completes.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <zlib.h>

#include <atomic>
#include <iostream>
#include <map>

#include "tests/support/files.h"
#include "tests/support/hostile_bytes.h"
#include "tests/support/postgres.h"
#include "tests/support/proc_memory.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using papernet::test::draco_header;
using papernet::test::varint;
using namespace papernet::test;

// Both stores.
class HostileHttp : public BothStores {};
INSTANTIATE_BOTH_STORES(HostileHttp);

namespace {

// A closed tetrahedron: unfolds at once, so "a normal job" costs nothing.
constexpr const char* kTetraObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

struct RawResponse {
  int status = 0;
  std::map<std::string, std::string> headers;  // lower-case names
  std::string body;
  json problem() const { return json::parse(body, nullptr, false); }
};

// One TCP connection to the server, byte for byte what the test writes.
class RawConnection {
 public:
  explicit RawConnection(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  bool connected() const { return connected_; }

  /// False once the server has closed (or reset) the connection.
  bool send(std::string_view data) {
    while (!data.empty()) {
      const ssize_t n = ::send(fd_, data.data(), data.size(), MSG_NOSIGNAL);
      if (n <= 0) return false;
      data.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
  }
  void close_write() { ::shutdown(fd_, SHUT_WR); }
  /// True when the server has sent something (an answer) or closed.
  bool readable() {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, 0) > 0;
  }

  /// The next response (its head, and its body by Content-Length or until close); status 0
  /// when the connection ended or `timeout` passed before a whole head arrived.
  RawResponse read_response(std::chrono::seconds timeout = 60s) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    RawResponse r;
    std::size_t head_end;
    while ((head_end = in_.find("\r\n\r\n")) == std::string::npos)
      if (!receive(end)) return r;
    std::istringstream head(in_.substr(0, head_end));
    std::string line;
    std::getline(head, line);
    if (line.size() > 12) r.status = std::atoi(line.c_str() + 9);
    while (std::getline(head, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const auto colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::string name = line.substr(0, colon);
      for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      r.headers[name] = line.substr(line.find_first_not_of(' ', colon + 1));
    }
    in_.erase(0, head_end + 4);
    const std::size_t length = r.headers.count("content-length")
                                   ? std::stoul(r.headers["content-length"])
                                   : std::string::npos;
    while (in_.size() < length && receive(end)) {
    }
    r.body = in_.substr(0, std::min(length, in_.size()));
    in_.erase(0, r.body.size());
    return r;
  }

  /// True when the server closes the connection within `timeout` (what it still sends is read
  /// and dropped).
  bool closed_by_server(std::chrono::seconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      char buf[4096];
      if (::recv(fd_, buf, sizeof buf, 0) <= 0) return true;
    }
    return false;
  }

 private:
  bool receive(std::chrono::steady_clock::time_point end) {
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      if (left.count() <= 0) return false;
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long>(left.count(), 200)));
      if (ready < 0) return false;
      if (ready == 0) continue;
      char buf[65536];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) return false;
      in_.append(buf, static_cast<std::size_t>(n));
      return true;
    }
  }

  int fd_ = -1;
  bool connected_ = false;
  std::string in_;
};

void expect_raw_problem(const RawResponse& res, int status, const std::string& code,
                        const std::string& detail_has = "") {
  EXPECT_EQ(res.status, status) << res.body;
  EXPECT_EQ(res.headers.count("content-type") ? res.headers.at("content-type") : "",
            "application/problem+json");
  const json doc = res.problem();
  ASSERT_TRUE(doc.is_object()) << res.body;
  EXPECT_EQ(doc["code"], code) << res.body;
  EXPECT_EQ(doc["status"], status);
  EXPECT_NE(doc.value("detail", "").find(detail_has), std::string::npos) << res.body;
}

void expect_problem_naming(const httplib::Result& res, int status, const std::string& code,
                           const std::string& detail_has) {
  papernet::test::expect_problem(res, status, code);
  if (res) {
    EXPECT_NE(res->body.find(detail_has), std::string::npos) << res->body;
  }
}

// A job's failure: the job says why, and its result URL answers with that problem.
json expect_job_fails(const Server& s, const std::string& id, int status, const std::string& code,
                      const std::string& detail_has = "") {
  const json job = wait_final(s, id);
  EXPECT_EQ(job["status"], "failed") << job.dump();
  EXPECT_EQ(job["error"]["code"], code) << job.dump();
  EXPECT_NE(job["error"].value("detail", "").find(detail_has), std::string::npos) << job.dump();
  expect_problem(s.client().Get("/v1/jobs/" + id + "/net.json"), status, code);
  return job;
}

void expect_normal_job_completes(const Server& s) {
  const json job = wait_final(s, submit(s, kTetraObj, "model/obj", "?strategy=TU"));
  EXPECT_EQ(job["status"], "succeeded") << job.dump();
}

std::string post_head(const std::string& headers) {
  return "POST /v1/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: model/obj\r\n" + headers +
         "\r\n";
}

std::string gzip(const std::string& data) {
  z_stream z{};
  deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&z, data.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::size_t job_count(const Server& s) {
  return body(s.client().Get("/v1/jobs?limit=100"))["jobs"].size();
}

}  // namespace

// Over --max-body-bytes: a declared length is refused before a byte of the body is read; a
// chunked, length-less or gzip-encoded body is cut off at the limit. The server's peak memory
// stays where it was although 24 MB were offered.
TEST_P(HostileHttp, OversizedBodiesAreRefusedWithoutBeingBuffered) {
  Server s({"--workers", "1", "--max-body-bytes", "200000", "--reuse-results", "false"});
  const std::size_t peak_before = proc_status_kb(s.pid(), "VmHWM");
  {
    RawConnection c(s.port());
    ASSERT_TRUE(c.send(post_head("Content-Length: 1000000000000\r\n")));
    expect_raw_problem(c.read_response(), 413, "payload_too_large", "declares 1000000000000 bytes");
    EXPECT_TRUE(c.closed_by_server(30s));
  }
  {  // curl's way for big uploads: the body follows only after "100 Continue".
    RawConnection c(s.port());
    ASSERT_TRUE(c.send(post_head("Content-Length: 5000000000\r\nExpect: 100-continue\r\n")));
    expect_raw_problem(c.read_response(), 413, "payload_too_large");
  }
  // Streams 8 MB in the given framing while another thread reads the answer.
  auto stream = [&](const std::string& head, bool chunked) {
    RawConnection c(s.port());
    EXPECT_TRUE(c.send(head));
    std::atomic<std::size_t> sent{0};
    std::thread sender([&] {
      const std::string block(64 << 10, 'v');
      const std::string chunk = chunked ? "10000\r\n" + block + "\r\n" : block;
      while (sent < (8u << 20) && c.send(chunk)) sent += block.size();
      c.close_write();
    });
    RawResponse res = c.read_response();
    sender.join();
    return std::make_pair(res, sent.load());
  };
  const auto [chunked, chunked_sent] = stream(post_head("Transfer-Encoding: chunked\r\n"), true);
  expect_raw_problem(chunked, 413, "payload_too_large", "200000");
  // A body that would end only when the connection closes is not read at all.
  const auto [no_length, no_length_sent] = stream(post_head("Connection: close\r\n"), false);
  expect_raw_problem(no_length, 411, "length_required", "Content-Length");
  std::cout << "[ figures  ] chunked: " << chunked_sent
            << " bytes offered; no length: " << no_length_sent << " bytes offered\n";

  // 8 MB of zeros in 8 KB of gzip: the limit counts what the body decodes to.
  const std::string bomb = gzip(std::string(8u << 20, '0'));
  {
    RawConnection c(s.port());
    ASSERT_TRUE(c.send(post_head("Content-Encoding: gzip\r\nContent-Length: " +
                                 std::to_string(bomb.size()) + "\r\n") +
                       bomb));
    expect_raw_problem(c.read_response(), 413, "payload_too_large");
  }
  {  // A route that takes no body does not read a chunked one.
    RawConnection c(s.port());
    ASSERT_TRUE(
        c.send("DELETE /v1/jobs/0123456789abcdef0123456789abcdef HTTP/1.1\r\nHost: x\r\n"
               "Transfer-Encoding: chunked\r\n\r\n10000\r\n"));
    expect_raw_problem(c.read_response(), 413, "payload_too_large", "takes no request body");
  }
  EXPECT_EQ(job_count(s), 0u) << "no refused upload became a job";
  expect_normal_job_completes(s);
  const std::size_t peak_after = proc_status_kb(s.pid(), "VmHWM");
  std::cout << "[ figures  ] server peak RSS " << peak_before << " kB before, " << peak_after
            << " kB after\n";
  expect_memory_growth_below(peak_before, peak_after, 16 * 1024,
                             "the server buffered a refused body");
}

// A client that closes mid-body leaves no job behind, in any framing.
TEST_P(HostileHttp, TruncatedUploadsCreateNoJob) {
  Server s({"--workers", "1", "--reuse-results", "false"});
  const std::string mesh = test_mesh("sample.obj");
  const std::string boundary = "xyzzy";
  const std::string multipart = "--" + boundary +
                                "\r\nContent-Disposition: form-data; name=\"mesh\"; "
                                "filename=\"a.obj\"\r\nContent-Type: model/obj\r\n\r\n" +
                                mesh + "\r\n--" + boundary + "--\r\n";
  const std::vector<std::string> truncated = {
      post_head("Content-Length: " + std::to_string(mesh.size()) + "\r\n") +
          mesh.substr(0, mesh.size() / 2),
      post_head("Transfer-Encoding: chunked\r\n") + "2000\r\n" + mesh.substr(0, 0x2000) +
          "\r\n1000\r\n" + mesh.substr(0, 100),
      "POST /v1/jobs HTTP/1.1\r\nHost: x\r\nContent-Type: multipart/form-data; boundary=" +
          boundary + "\r\nContent-Length: " + std::to_string(multipart.size()) + "\r\n\r\n" +
          multipart.substr(0, multipart.size() - 100)};
  for (const std::string& request : truncated) {
    RawConnection c(s.port());
    ASSERT_TRUE(c.send(request));
    c.close_write();
    EXPECT_TRUE(c.closed_by_server(30s));
  }
  // The multipart body whole but its closing boundary missing: the request is malformed.
  {
    RawConnection c(s.port());
    const std::string cut = multipart.substr(0, multipart.size() - 12);
    ASSERT_TRUE(
        c.send("POST /v1/jobs HTTP/1.1\r\nHost: x\r\nContent-Type: multipart/form-data; "
               "boundary=" +
               boundary + "\r\nContent-Length: " + std::to_string(cut.size()) + "\r\n\r\n" + cut));
    expect_raw_problem(c.read_response(), 400, "malformed_request");
  }
  EXPECT_EQ(s.client().Get("/healthz")->status, 200);
  EXPECT_EQ(job_count(s), 0u);
  expect_normal_job_completes(s);
  EXPECT_EQ(job_count(s), 1u);
}

// Slow clients: headers trickled past --header-timeout, a body that stops (read timeout), a body
// trickled past --request-timeout, and more silent connections than HTTP threads. Each is cut
// off; everyone else is served meanwhile.
// (--max-streams 0: no threads beside the four, which the silent connections outnumber.)
TEST_P(HostileHttp, SlowClientsAreTimedOutAndOthersAreServed) {
  Server s({"--workers", "1", "--http-threads", "4", "--max-streams", "0", "--read-timeout", "1",
            "--header-timeout", "2", "--request-timeout", "4", "--reuse-results", "false"});
  std::atomic<bool> stop{false};
  auto trickle = [&](RawConnection& c, const std::string& bytes, std::chrono::milliseconds gap) {
    for (char ch : bytes) {
      // Once the server has answered, sending on would only make it reset the connection.
      if (stop || c.readable() || !c.send(std::string(1, ch))) return;
      std::this_thread::sleep_for(gap);
    }
  };
  RawConnection headers(s.port()), stalled(s.port()), slow_body(s.port());
  ASSERT_TRUE(headers.send("POST /v1/jobs HTTP/1.1\r\n"));
  std::thread t1(trickle, std::ref(headers), std::string(200, 'X'), 200ms);
  ASSERT_TRUE(stalled.send(post_head("Content-Length: 1000\r\n") + "v 0 0 0\n"));
  ASSERT_TRUE(slow_body.send(post_head("Content-Length: 100000\r\n")));
  std::thread t2(trickle, std::ref(slow_body), std::string(5000, 'v'), 100ms);

  expect_normal_job_completes(s);
  expect_raw_problem(headers.read_response(), 408, "request_timeout");
  expect_raw_problem(stalled.read_response(), 408, "request_timeout");
  expect_raw_problem(slow_body.read_response(), 408, "request_timeout");
  stop = true;
  t1.join();
  t2.join();
  EXPECT_TRUE(headers.closed_by_server(30s));
  EXPECT_TRUE(stalled.closed_by_server(30s));

  // Six connections that send nothing, four HTTP threads: they are dropped, others get through.
  std::vector<std::unique_ptr<RawConnection>> silent;
  for (int i = 0; i < 6; ++i) silent.push_back(std::make_unique<RawConnection>(s.port()));
  auto res = s.client().Get("/healthz");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  for (auto& c : silent) EXPECT_TRUE(c->closed_by_server(30s));
  EXPECT_EQ(job_count(s), 1u);
}

TEST_P(HostileHttp, WrongContentTypesAre415) {
  Server s({"--workers", "1", "--reuse-results", "false"});
  auto c = s.client();
  for (const char* type : {"image/png", "text/html", "application/zip", "video/mp4"})
    expect_problem(c.Post("/v1/jobs", kTetraObj, type), 415, "unsupported_format");
  expect_problem(c.Post("/v1/jobs?format=exe", kTetraObj, "model/obj"), 415, "unsupported_format");
  expect_problem(c.Post("/v1/jobs",
                        "\x7f"
                        "ELF\x02\x01\x01",
                        "application/octet-stream"),
                 415, "unsupported_format");
  httplib::MultipartFormDataItems jpeg = {{"mesh", kTetraObj, "a.jpg", "image/jpeg"}};
  expect_problem(c.Post("/v1/jobs", jpeg), 415, "unsupported_format");
  expect_problem(c.Post("/v1/jobs", kTetraObj, "multipart/form-data"), 400, "malformed_request");
  EXPECT_EQ(job_count(s), 0u);
  expect_normal_job_completes(s);
}

// Headers that claim a billion elements are refused by the loader before it allocates: a count
// the file contradicts is unreadable (422), a count over the server's limit is too large (413),
// and so is a real mesh over --max-faces (it was 422 above 4 x max-faces before). Peak memory
// does not move.
TEST_P(HostileHttp, HugeDeclaredCountsAreRefusedBeforeAllocating) {
  Server s({"--workers", "1", "--max-faces", "200", "--reuse-results", "false"});
  const std::size_t peak_before = proc_status_kb(s.pid(), "VmHWM");
  const std::string ply_faces =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
      "float z\nelement face 1000000000\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::string ply_vertices = ply_faces;
  ply_vertices.replace(ply_vertices.find("vertex 3"), 8, "vertex 1000000000");
  ply_vertices.replace(ply_vertices.find("face 1000000000"), 15, "face 1");
  std::string stl(84, '\0');
  stl += std::string(50, '\0');
  const std::uint32_t triangles = 1000000000;
  std::memcpy(stl.data() + 80, &triangles, 4);
  const std::string draco_faces = draco_header(1, 1) + '\0' + varint(3) + varint(1u << 30) + '\0' +
                                  varint(1) + varint(0) + std::string(16, '\0');
  const std::string draco_points =
      draco_header(1, 0) + varint(1) + varint(1000000000) + std::string(16, '\0');

  struct Case {
    std::string name, mesh, type;
    int status;
    std::string code, detail;
  };
  const std::vector<Case> cases = {
      {"ply faces", ply_faces, "model/x-ply", 422, "unreadable_mesh", "declares 1000000000"},
      {"ply vertices", ply_vertices, "model/x-ply", 422, "unreadable_mesh", "declares 1000000000"},
      {"off", "OFF\n1000000000 1000000000 0\n0 0 0\n", "model/x-off", 422, "unreadable_mesh",
       "declares 1000000000"},
      {"stl", stl, "model/stl", 422, "unreadable_mesh", "1000000000"},
      {"draco faces", draco_faces, "model/x-draco", 413, "too_many_faces", "1073741824"},
      {"draco points", draco_points, "model/x-draco", 422, "unreadable_mesh", "1000000000"},
      {"obj over max-faces", test_mesh("sample.obj"), "model/obj", 413, "too_many_faces",
       "limit of 200"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    expect_job_fails(s, submit(s, c.mesh, c.type), c.status, c.code, c.detail);
  }
  // A glTF accessor claiming a billion elements, with its buffer uploaded beside it.
  json gltf = json::parse(test_mesh("gltf_external/Box.gltf"));
  gltf["accessors"][0]["count"] = 1000000000;
  httplib::MultipartFormDataItems items = {
      {"mesh", gltf.dump(), "Box.gltf", "model/gltf+json"},
      {"buffers", test_mesh("gltf_external/Box0.bin"), "Box0.bin", "application/octet-stream"}};
  auto res = s.client().Post("/v1/jobs", items);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 202) << res->body;
  expect_job_fails(s, body(res)["id"], 422, "unreadable_mesh", "declares 1000000000");

  expect_normal_job_completes(s);
  const std::size_t peak_after = proc_status_kb(s.pid(), "VmHWM");
  std::cout << "[ figures  ] server peak RSS " << peak_before << " kB before, " << peak_after
            << " kB after\n";
  expect_memory_growth_below(peak_before, peak_after, 64 * 1024, "peak memory");
}

TEST_P(HostileHttp, NonFiniteCoordinatesAreInvalidMeshes) {
  Server s({"--workers", "1", "--reuse-results", "false"});
  std::string tetra = kTetraObj;
  for (const char* value : {"nan", "inf", "-inf", "NaN"}) {
    SCOPED_TRACE(value);
    std::string mesh = tetra;
    mesh.replace(mesh.find("v 1 0 0"), 7, std::string("v ") + value + " 0 0");
    const json job =
        expect_job_fails(s, submit(s, mesh, "model/obj"), 422, "invalid_mesh", "non-finite");
    EXPECT_EQ(job["error"]["reasons"][0]["code"], "non_finite_coordinates") << job.dump();
  }
  expect_job_fails(s, submit(s, "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "model/x-off"), 422,
                   "invalid_mesh", "non-finite");
  // A number too large for a double is no coordinate at all: the file is unreadable.
  std::string huge = tetra;
  huge.replace(huge.find("v 1 0 0"), 7, "v 1e400 0 0");
  expect_job_fails(s, submit(s, huge, "model/obj"), 422, "unreadable_mesh", "obj line 2");
  expect_normal_job_completes(s);
}

// JSON carries UTF-8 only, and what the service quotes from a request is bytes: an option's
// value or name, a bad token of a mesh, an OBJ's material names. Each invalid byte is quoted as
// U+FFFD, in answers and stored jobs alike; before, nlohmann's dump threw and the answer was a
// 500 (a fuzz_options finding, docs/reliability.md).
TEST_P(HostileHttp, BytesThatAreNotUtf8AreQuotedAsReplacementCharacters) {
  Server s({"--workers", "1", "--reuse-results", "false"});
  const std::string replacement = "\xEF\xBF\xBD";
  auto c = s.client();
  expect_problem_naming(c.Post("/v1/jobs?paper=A%C5", kTetraObj, "model/obj"), 400,
                        "invalid_option_value", "A" + replacement);
  expect_problem_naming(c.Post("/v1/jobs?se%C5ed=1", kTetraObj, "model/obj"), 400, "unknown_option",
                        "se" + replacement + "ed");
  // A URL is ASCII: the byte is refused, not quoted on.
  expect_problem_naming(
      c.Post("/v1/jobs?callback_url=http://127.0.0.1/a%C5", kTetraObj, "model/obj"), 400,
      "invalid_option_value", "outside ASCII");
  std::string tetra = kTetraObj;
  const json failed = expect_job_fails(s, submit(s, tetra + "f 1 2 \xC5x\n", "model/obj"), 422,
                                       "unreadable_mesh", "'" + replacement + "x'");
  EXPECT_EQ(failed["error"]["detail"], "obj line 9: bad face index '" + replacement + "x'");
  // Material names from the file: the job succeeds, its net names them.
  const json job = wait_final(s, submit(s, "mtllib \xC5.mtl\nusemtl m\xC5\n" + tetra, "model/obj"));
  ASSERT_EQ(job["status"], "succeeded") << job.dump();
  auto net = c.Get("/v1/jobs/" + job["id"].get<std::string>() + "/net.json");
  ASSERT_TRUE(net);
  ASSERT_EQ(net->status, 200);
  const json doc = json::parse(net->body);
  EXPECT_EQ(doc["materials"][0]["name"], "m" + replacement) << net->body.substr(0, 2000);
  EXPECT_EQ(job_count(s), 2u);
  expect_normal_job_completes(s);
}

// Job ids are opaque: traversal, encoded dots, NUL and very long ids name no job and no file.
TEST_P(HostileHttp, PathLikeJobIdsNameNothing) {
  Server s({"--workers", "1"});
  const std::string long_id(5000, 'a');
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"GET /v1/jobs/%2e%2e", "job_not_found"},
      {"GET /v1/jobs/%2E%2E%2F%2E%2E%2Fetc%2Fpasswd", "not_found"},
      {"GET /v1/jobs/../../etc/passwd", "not_found"},
      {"GET /v1/jobs/..%2f..%2fetc%2fpasswd/net.json", "not_found"},
      {"GET /v1/jobs/%2e%2e/net.json", "job_not_found"},
      {"GET /v1/jobs/0123456789abcdef0123456789abcdef%00/net.json", "job_not_found"},
      {"GET /v1/jobs/abc%00def", "job_not_found"},
      {"DELETE /v1/jobs/%2e%2e", "job_not_found"},
      {"GET /v1/jobs/" + long_id, "job_not_found"},
      {"GET /v1/jobs/" + long_id + "/events", "job_not_found"},
  };
  for (const auto& [request, code] : cases) {
    SCOPED_TRACE(request.substr(0, 80));
    RawConnection c(s.port());
    ASSERT_TRUE(c.send(request + " HTTP/1.1\r\nHost: x\r\n\r\n"));
    const RawResponse res = c.read_response();
    expect_raw_problem(res, 404, code);
    EXPECT_EQ(res.body.find("root:"), std::string::npos);
    EXPECT_LT(res.body.size(), 1000u) << "the answer does not echo a whole long id";
  }
  {  // Longer than a request line may be.
    RawConnection c(s.port());
    ASSERT_TRUE(c.send("GET /v1/jobs/" + std::string(10000, 'a') + " HTTP/1.1\r\nHost: x\r\n\r\n"));
    expect_raw_problem(c.read_response(), 414, "uri_too_long");
  }
  {  // Endless headers: cut off at 64 KiB, not buffered.
    RawConnection c(s.port());
    std::string head = "GET /healthz HTTP/1.1\r\n";
    for (int i = 0; i < 2000; ++i)
      head += "X-Filler-" + std::to_string(i) + ": " + std::string(100, 'f') + "\r\n";
    c.send(head);
    expect_raw_problem(c.read_response(), 431, "request_head_too_large");
  }
  {  // A request line that never ends.
    RawConnection c(s.port());
    c.send("GET /" + std::string(1 << 20, 'a'));
    EXPECT_TRUE(c.closed_by_server(30s));
  }
  expect_normal_job_completes(s);
}

// glTF buffer URIs are keys into the upload, never paths: file URIs, traversal and absolute
// paths fail the job naming the URI, and no server file appears in any answer.
TEST_P(HostileHttp, GltfBufferUrisNeverReadServerFiles) {
  Server s({"--workers", "1", "--reuse-results", "false"});
  const json box = json::parse(test_mesh("gltf_external/Box.gltf"));
  for (const char* uri : {"file:///etc/passwd", "../../etc/passwd", "/etc/passwd",
                          "%2e%2e/%2e%2e/etc/passwd", "file:/etc/passwd", "/proc/self/environ"}) {
    SCOPED_TRACE(uri);
    json gltf = box;
    gltf["buffers"][0]["uri"] = uri;
    const json job =
        expect_job_fails(s, submit(s, gltf.dump(), "model/gltf+json"), 422, "unreadable_mesh");
    EXPECT_EQ(job.dump().find("root:"), std::string::npos);
    EXPECT_NE(job["error"]["detail"].get<std::string>().find("not supplied"), std::string::npos)
        << job.dump();
  }
  // A buffers part whose file name is a path is refused at once.
  for (const char* name : {"../../etc/passwd", "/etc/passwd", "..\\..\\boot.ini"}) {
    SCOPED_TRACE(name);
    httplib::MultipartFormDataItems items = {
        {"mesh", box.dump(), "Box.gltf", "model/gltf+json"},
        {"buffers", test_mesh("gltf_external/Box0.bin"), name, "application/octet-stream"}};
    expect_problem(s.client().Post("/v1/jobs", items), 400, "malformed_request");
  }
  expect_normal_job_completes(s);
}

// JSON nested ten thousand deep: in the options part it is refused at POST (400), in a glTF the
// job fails naming the depth; the server neither overflows its stack nor builds the document.
TEST_P(HostileHttp, DeeplyNestedJsonIsRefused) {
  Server s({"--workers", "1", "--reuse-results", "false"});
  const std::size_t peak_before = proc_status_kb(s.pid(), "VmHWM");
  auto nested_object = [](int depth) {
    std::string text;
    for (int i = 0; i < depth; ++i) text += "{\"a\":";
    text += "1";
    text += std::string(static_cast<std::size_t>(depth), '}');
    return text;
  };
  for (const std::string& options : {nested_object(10000), "{\"seed\":" + std::string(30000, '[') +
                                                               std::string(30000, ']') + "}"}) {
    httplib::MultipartFormDataItems items = {{"mesh", kTetraObj, "t.obj", "model/obj"},
                                             {"options", options, "", "application/json"}};
    expect_problem_naming(s.client().Post("/v1/jobs", items), 400, "malformed_options", "deeper");
  }
  // 2 MB of options: longer than any real options document.
  httplib::MultipartFormDataItems long_options = {
      {"mesh", kTetraObj, "t.obj", "model/obj"},
      {"options", "{\"seed\":1" + std::string(2 << 20, ' ') + "}", "", "application/json"}};
  expect_problem(s.client().Post("/v1/jobs", long_options), 400, "malformed_options");

  std::string gltf = test_mesh("gltf_external/Box.gltf");
  gltf.erase(gltf.rfind('}'));
  gltf += ",\"extras\":" + nested_object(10000) + "}";
  expect_job_fails(s, submit(s, gltf, "model/gltf+json"), 422, "unreadable_mesh", "deeper");
  expect_job_fails(s, submit(s, std::string(1 << 20, '['), "model/gltf+json"), 422,
                   "unreadable_mesh");
  expect_normal_job_completes(s);
  const std::size_t peak_after = proc_status_kb(s.pid(), "VmHWM");
  std::cout << "[ figures  ] server peak RSS " << peak_before << " kB before, " << peak_after
            << " kB after\n";
  expect_memory_growth_below(peak_before, peak_after, 64 * 1024, "peak memory");
}

// The HTTP edges: a POST without a length, methods a route does not take, a second cancel.
TEST_P(HostileHttp, LengthlessPostIs411AndOtherMethodsAre405WithAllow) {
  Server s({"--workers", "1"});
  {  // No Content-Length, no chunking: 411 at once (not a read timeout's 408).
    RawConnection c(s.port());
    ASSERT_TRUE(c.send(post_head("")));
    expect_raw_problem(c.read_response(), 411, "length_required", "Content-Length");
  }
  struct Case {
    std::string method, path, allow;
  };
  const std::string job = "/v1/jobs/0123456789abcdef0123456789abcdef";
  const Case cases[] = {
      {"PUT", "/v1/jobs", "GET, HEAD, POST"},     {"DELETE", "/v1/jobs", "GET, HEAD, POST"},
      {"OPTIONS", "/v1/jobs", "GET, HEAD, POST"}, {"PATCH", "/v1/jobs", "GET, HEAD, POST"},
      {"POST", job, "GET, HEAD, DELETE"},         {"PUT", job, "GET, HEAD, DELETE"},
      {"DELETE", job + "/net.json", "GET, HEAD"}, {"POST", job + "/events", "GET, HEAD"},
      {"POST", "/metrics", "GET, HEAD"}};
  for (const Case& k : cases) {
    SCOPED_TRACE(k.method + " " + k.path);
    RawConnection c(s.port());
    ASSERT_TRUE(
        c.send(k.method + " " + k.path + " HTTP/1.1\r\nHost: x\r\nContent-Length: 4\r\n\r\nv 0\n"));
    const RawResponse res = c.read_response();
    expect_raw_problem(res, 405, "method_not_allowed", k.method);
    EXPECT_EQ(res.headers.count("allow") ? res.headers.at("allow") : "", k.allow);
  }
  // Unknown paths stay 404 whatever the method.
  expect_problem(s.client().Put("/v1/nothing", "x", "text/plain"), 404, "not_found");

  // A job cancelled once is finished: cancelling it again is 409, as for any finished job.
  const std::string id = submit(s, kTetraObj, "model/obj", "?strategy=TU");
  const json done = wait_final(s, id);
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  expect_problem(s.client().Delete("/v1/jobs/" + id), 409, "job_finished");
  expect_normal_job_completes(s);
}
