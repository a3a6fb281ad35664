// The web demo directory served at / (server/static_files.h).
#include "server/static_files.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace papernet::server {
namespace {

TEST(StaticFiles, NothingIsServedWithoutADirectory) {
  httplib::Server http;
  EXPECT_NO_THROW(mount_web_root(http, ""));
  http.Get("/healthz", [](const httplib::Request&, httplib::Response& res) {
    res.set_content("ok", "text/plain");
  });
  const int port = http.bind_to_any_port("127.0.0.1");
  ASSERT_GT(port, 0);
  std::thread thread([&] { http.listen_after_bind(); });
  httplib::Client client("127.0.0.1", port);
  auto index = client.Get("/");
  http.stop();
  thread.join();
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 404);
}

TEST(StaticFiles, ANonDirectoryIsRefusedByName) {
  httplib::Server http;
  try {
    mount_web_root(http, "/nonexistent/papernet-web");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/papernet-web"), std::string::npos);
  }
}

TEST(StaticFiles, TheDirectoryIsServedAtTheRootBesideTheRoutes) {
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("papernet-web-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "index.html") << "<!doctype html><title>demo</title>";
  httplib::Server http;
  http.Get("/healthz", [](const httplib::Request&, httplib::Response& res) {
    res.set_content("ok", "text/plain");
  });
  mount_web_root(http, dir.string());
  const int port = http.bind_to_any_port("127.0.0.1");
  ASSERT_GT(port, 0);
  std::thread thread([&] { http.listen_after_bind(); });
  httplib::Client client("127.0.0.1", port);
  auto index = client.Get("/");
  auto health = client.Get("/healthz");
  auto missing = client.Get("/nothing-here.js");
  http.stop();
  thread.join();
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(index && health && missing);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->body, "<!doctype html><title>demo</title>");
  EXPECT_EQ(index->get_header_value("Content-Type"), "text/html");
  EXPECT_EQ(index->get_header_value("Cache-Control"), "no-cache");
  EXPECT_EQ(health->body, "ok");
  EXPECT_EQ(missing->status, 404);
}

}  // namespace
}  // namespace papernet::server
