#include "server/config.h"

#include <gtest/gtest.h>

#include <map>
#include <vector>

using namespace papernet::server;

namespace {

struct Args {
  std::vector<std::string> words;
  std::vector<char*> argv;
  explicit Args(std::vector<std::string> w) : words(std::move(w)) {
    for (auto& s : words) argv.push_back(s.data());
  }
  int argc() const { return static_cast<int>(argv.size()); }
};

std::optional<ServerConfig> parse(std::vector<std::string> words,
                                  std::map<std::string, std::string> env = {}) {
  words.insert(words.begin(), "serve");
  Args args(std::move(words));
  return parse_serve_config(args.argc(), args.argv.data(), [&env](const char* name) {
    auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  });
}

}  // namespace

TEST(ConfigTest, DefaultsAreLoopbackPort8080AndVar) {
  const ServerConfig c = *parse({});
  EXPECT_EQ(c.host, "127.0.0.1");
  EXPECT_EQ(c.port, 8080);
  EXPECT_EQ(c.data_dir, "./var");
  EXPECT_GE(c.workers, 1u);
  EXPECT_TRUE(c.reuse_results);
  EXPECT_EQ(c.web_root, "") << "no web demo unless asked for";
}

TEST(ConfigTest, WebRootFromEnvironmentOrFlag) {
  EXPECT_EQ(parse({}, {{"PAPERNET_WEB_ROOT", "/srv/web"}})->web_root, "/srv/web");
  EXPECT_EQ(parse({"--web-root", "dist"}, {{"PAPERNET_WEB_ROOT", "/srv/web"}})->web_root, "dist");
}

TEST(ConfigTest, EnvironmentThenFlagsWhichWin) {
  const ServerConfig c =
      *parse({"--port", "9000", "--queue-length=5"},
             {{"PAPERNET_PORT", "7000"}, {"PAPERNET_WORKERS", "3"}, {"PAPERNET_DATA", "/tmp/x"}});
  EXPECT_EQ(c.port, 9000);
  EXPECT_EQ(c.workers, 3u);
  EXPECT_EQ(c.data_dir, "/tmp/x");
  EXPECT_EQ(c.queue_length, 5u);
}

TEST(ConfigTest, ClientTimeouts) {
  const ServerConfig d = *parse({});
  EXPECT_EQ(d.read_timeout, 5);
  EXPECT_EQ(d.header_timeout, 10);
  EXPECT_EQ(d.request_timeout, 120);
  const ServerConfig c =
      *parse({"--read-timeout", "1.5", "--header-timeout=3"}, {{"PAPERNET_REQUEST_TIMEOUT", "30"}});
  EXPECT_EQ(c.read_timeout, 1.5);
  EXPECT_EQ(c.header_timeout, 3);
  EXPECT_EQ(c.request_timeout, 30);
  EXPECT_THROW(parse({"--read-timeout", "0"}), ConfigError);
  EXPECT_THROW(parse({"--header-timeout", "-1"}), ConfigError);
}

TEST(ConfigTest, BadValuesNameTheirSource) {
  try {
    parse({"--port", "99999"});
    ADD_FAILURE() << "accepted port 99999";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--port"), std::string::npos) << e.what();
  }
  try {
    parse({}, {{"PAPERNET_WORKERS", "many"}});
    ADD_FAILURE() << "accepted workers=many";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("PAPERNET_WORKERS"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse({"--colour", "red"}), ConfigError);
  EXPECT_THROW(parse({"--port"}), ConfigError);
  EXPECT_THROW(parse({"--job-time-limit", "700"}), ConfigError);  // above the max (600)
}

TEST(ConfigTest, HelpListsEveryVariable) {
  EXPECT_FALSE(parse({"--help"}));
  const std::string help = serve_usage();
  for (const char* v : {"PAPERNET_HOST", "PAPERNET_PORT", "PAPERNET_DATA", "PAPERNET_WORKERS",
                        "PAPERNET_QUEUE_LENGTH", "PAPERNET_MAX_BODY_BYTES", "PAPERNET_MAX_FACES",
                        "PAPERNET_JOB_TIME_LIMIT"})
    EXPECT_NE(help.find(v), std::string::npos) << v;
}

TEST(ConfigTest, CorsOriginsAreCheckedOrigins) {
  EXPECT_TRUE(parse({})->cors_origins.empty());
  const auto c = *parse({"--cors-origins", " https://shop.example/, http://localhost:5173 "});
  EXPECT_EQ(c.cors_origins,
            (std::vector<std::string>{"https://shop.example", "http://localhost:5173"}));
  EXPECT_EQ(parse({}, {{"PAPERNET_CORS_ORIGINS", "*"}})->cors_origins,
            std::vector<std::string>{"*"});
  for (const char* bad :
       {"shop.example", "https://shop.example/path", "ftp://x", "https://", "https://*.example"})
    EXPECT_THROW(parse({"--cors-origins", bad}), ConfigError) << bad;
}

TEST(ConfigTest, ApiKeysRefuseAnyOrigin) {
  EXPECT_EQ(parse({"--api-keys", "/etc/papernet/keys"})->api_keys, "/etc/papernet/keys");
  EXPECT_THROW(parse({"--api-keys", "keys", "--cors-origins", "*"}), ConfigError);
  EXPECT_EQ(parse({"--api-keys", "keys"}, {{"PAPERNET_CORS_ORIGINS", "https://shop.example"}})
                ->cors_origins.size(),
            1u);
}

TEST(ConfigTest, RetentionIsADuration) {
  EXPECT_EQ(parse({})->retention, 7 * 86400);
  EXPECT_EQ(parse({"--retention", "3600"})->retention, 3600);
  EXPECT_EQ(parse({"--retention", "90m"})->retention, 5400);
  EXPECT_EQ(parse({}, {{"PAPERNET_RETENTION", "2d"}})->retention, 2 * 86400);
  EXPECT_EQ(parse({"--retention", "0"})->retention, 0);
  for (const char* bad : {"", "d", "7w", "-1", "1e9d", "soon"})
    EXPECT_THROW(parse({"--retention", bad}), ConfigError) << bad;
}

TEST(ConfigTest, MaxStoreIsASize) {
  EXPECT_EQ(parse({})->max_store_bytes, std::uint64_t{20} << 30);
  EXPECT_EQ(parse({"--max-store", "123456"})->max_store_bytes, 123456u);
  EXPECT_EQ(parse({"--max-store", "500M"})->max_store_bytes, std::uint64_t{500} << 20);
  EXPECT_EQ(parse({}, {{"PAPERNET_MAX_STORE", "2T"}})->max_store_bytes, std::uint64_t{2} << 40);
  EXPECT_EQ(parse({"--max-store", "0"})->max_store_bytes, 0u);
  for (const char* bad : {"", "G", "10GB", "-1", "1.5G", "99999999999T", "lots"})
    EXPECT_THROW(parse({"--max-store", bad}), ConfigError) << bad;
}
