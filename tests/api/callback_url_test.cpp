// A job's callback URL taken apart (api/callback_url.h, `parse_callback_url`): the host in lower
// case (an IPv6 address without its brackets), the port (80 unless given), the path and query the
// webhook asks for; and what the service cannot send to refused with a message naming why.
#include <gtest/gtest.h>

#include <string>

#include "api/callback_url.h"
#include "core/errors.h"

namespace papernet {
namespace {

TEST(CallbackUrl, IsTakenApartIntoHostPortAndTarget) {
  const CallbackUrl plain = parse_callback_url("http://Shop.Example.COM/hooks/papernet?k=1");
  EXPECT_EQ(plain.host, "shop.example.com");
  EXPECT_EQ(plain.port, 80);
  EXPECT_EQ(plain.target, "/hooks/papernet?k=1");

  const CallbackUrl bare = parse_callback_url("HTTP://10.0.0.7:8080");
  EXPECT_EQ(bare.host, "10.0.0.7");
  EXPECT_EQ(bare.port, 8080);
  EXPECT_EQ(bare.target, "/");

  const CallbackUrl query = parse_callback_url("http://receiver:9000?job=done");
  EXPECT_EQ(query.host, "receiver");
  EXPECT_EQ(query.port, 9000);
  EXPECT_EQ(query.target, "/?job=done") << "a query alone is asked of the root";

  const CallbackUrl six = parse_callback_url("http://[FD00::1]:65535/h");
  EXPECT_EQ(six.host, "fd00::1");
  EXPECT_EQ(six.port, 65535);
  EXPECT_EQ(six.target, "/h");
}

TEST(CallbackUrl, WhatCannotBeSentIsRefusedSayingWhy) {
  const struct {
    std::string url, why;
  } refused[] = {
      {"https://shop.example.com/h", "https is not supported"},
      {"ftp://shop.example.com/h", "is not an http:// URL"},
      {"http://user@shop.example.com/h", "has a user name"},
      {"http://shop.example.com/h#top", "has a fragment"},
      {"http://shop.example.com:0/h", "port that is not 1..65535"},
      {"http://shop.example.com:65536/h", "port that is not 1..65535"},
      {"http://shop.example.com:/h", "has an empty port"},
      {"http:///h", "has no host name"},
      {"http://shop_example/h", "has no host name"},
      {"http://[fd00::1/h", "has an unclosed ["},
      {"http://[fd00::1]x/h", "has text after ]"},
      {"http://[]/h", "has no IPv6 address"},
      {"http://shop.example.com/a b", "has a space"},
      {"http://shop.example.com/" + std::string(2048, 'a'), "longer than 2048 bytes"},
  };
  for (const auto& [url, why] : refused) {
    SCOPED_TRACE(url.substr(0, 60));
    try {
      parse_callback_url(url);
      ADD_FAILURE() << "accepted";
    } catch (const InvalidOptionException& e) {
      EXPECT_EQ(e.code(), "invalid_option_value");
      EXPECT_EQ(e.option(), "callback_url");
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace papernet
