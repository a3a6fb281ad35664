#include "api/options.h"

#include <gtest/gtest.h>

#include <cctype>
#include <exception>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "api/openapi.h"
#include "print/pages.h"
#include "tests/support/paths.h"

using namespace papernet;

namespace {

// The stable code of the InvalidOptionException that `f` throws ("" when it throws none).
template <class F>
std::string error_code(F f, std::string* option = nullptr) {
  try {
    f();
  } catch (const InvalidOptionException& e) {
    if (option) *option = e.option();
    return e.code();
  }
  return "";
}

}  // namespace

TEST(OptionsTest, DefaultsWhenNothingIsGiven) {
  const JobOptions o = parse_options_query({});
  EXPECT_EQ(o.strategy, Strategy::AUTO);
  EXPECT_EQ(parse_options_query({{"strategy", "auto"}}).strategy, Strategy::AUTO);
  EXPECT_EQ(o.seed, 1u);
  EXPECT_FALSE(o.target_faces);
  EXPECT_EQ(o.detail.mode, DetailMode::Auto);
  EXPECT_FALSE(o.time_limit);
  EXPECT_EQ(o.paper, "A4");
  EXPECT_EQ(o.tabs, TabMode::Auto);
  EXPECT_EQ(o.tab_room_budget, 100'000u);
  EXPECT_EQ(o.merge_budget, 480'000u);
  EXPECT_EQ(o.components, Components::All);
  EXPECT_FALSE(o.strict);
}

TEST(OptionsTest, DetailIsAutoFullOrAFaceCount) {
  EXPECT_EQ(parse_options_query({{"detail", "FULL"}}).detail.mode, DetailMode::Full);
  EXPECT_EQ(parse_options_query({{"detail", "auto"}}).detail.mode, DetailMode::Auto);
  const JobOptions n = parse_options_query({{"detail", "600"}});
  EXPECT_EQ(n.detail.mode, DetailMode::Faces);
  EXPECT_EQ(n.detail.faces, 600u);
  EXPECT_EQ(options_to_json(n)["detail"], 600);
  EXPECT_EQ(options_to_json(parse_options_query({}))["detail"], "auto");
  for (const char* bad : {"some", "-3", "2.5", "3"}) {
    try {
      parse_options_query({{"detail", bad}});
      ADD_FAILURE() << "detail=" << bad << " was accepted";
    } catch (const InvalidOptionException& e) {
      EXPECT_EQ(e.option(), "detail") << bad;
    }
  }
}

TEST(OptionsTest, QueryParametersAreParsed) {
  const JobOptions o = parse_options_query({{"strategy", "semp"},
                                            {"seed", "42"},
                                            {"target_faces", "500"},
                                            {"simplify", "800"},
                                            {"time_limit", "2.5"},
                                            {"size_mm", "120"},
                                            {"paper", "letter"},
                                            {"margin_mm", "5"},
                                            {"tabs", "false"},
                                            {"tab_room_budget", "0"},
                                            {"merge_budget", "0"},
                                            {"components", "largest"},
                                            {"strict", "yes"}});
  EXPECT_EQ(o.strategy, Strategy::SEMP);
  EXPECT_EQ(o.seed, 42u);
  EXPECT_EQ(o.target_faces, 500u);
  EXPECT_EQ(o.detail.mode, DetailMode::Faces);  // simplify: the older name of detail N
  EXPECT_EQ(o.detail.faces, 800u);
  EXPECT_DOUBLE_EQ(*o.time_limit, 2.5);
  EXPECT_DOUBLE_EQ(*o.size_mm, 120);
  EXPECT_EQ(o.paper, "Letter");
  EXPECT_DOUBLE_EQ(o.margin_mm, 5);
  EXPECT_EQ(o.tabs, TabMode::None);
  EXPECT_EQ(o.tab_room_budget, 0u);
  EXPECT_EQ(o.merge_budget, 0u);
  EXPECT_EQ(o.components, Components::Largest);
  EXPECT_TRUE(o.strict);
}

TEST(OptionsTest, ColourAndItsResolutionAreParsedAndChecked) {
  EXPECT_TRUE(JobOptions{}.colour);
  EXPECT_DOUBLE_EQ(JobOptions{}.dpi, 300);
  const JobOptions o = parse_options_query({{"colour", "none"}, {"dpi", "150"}});
  EXPECT_FALSE(o.colour);
  EXPECT_DOUBLE_EQ(o.dpi, 150);
  EXPECT_TRUE(parse_options_json(R"({"colour":"AUTO"})").colour);
  EXPECT_FALSE(parse_options_json(R"({"colour":false})").colour);
  EXPECT_EQ(error_code([] { parse_options_query({{"colour", "sepia"}}); }), "invalid_option_value");
  std::string option;
  EXPECT_EQ(error_code(
                [] {
                  parse_options_query({{"dpi", "20"}});
                },
                &option),
            "option_out_of_range");
  EXPECT_EQ(option, "dpi");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"dpi":5000})"); }), "option_out_of_range");
  const auto echo = options_to_json(o);
  EXPECT_EQ(echo.at("colour"), "none");
  EXPECT_EQ(echo.at("dpi"), 150);
}

TEST(OptionsTest, JsonObjectIsParsedWithTypedValues) {
  const JobOptions o = parse_options_json(
      R"({"strategy":"TU","seed":7,"scale":2.0,"paper":"none","tabs":false,"time_limit":null})");
  EXPECT_EQ(o.strategy, Strategy::TU);
  EXPECT_EQ(o.seed, 7u);
  EXPECT_DOUBLE_EQ(*o.scale, 2.0);
  EXPECT_EQ(o.paper, "none");
  EXPECT_EQ(o.tabs, TabMode::None);
  EXPECT_FALSE(o.time_limit);
}

TEST(OptionsTest, TabsTakeAModeOrABoolean) {
  EXPECT_EQ(parse_options_json(R"({"tabs":true})").tabs, TabMode::Auto);
  EXPECT_EQ(parse_options_json(R"({"tabs":false})").tabs, TabMode::None);
  EXPECT_EQ(parse_options_json(R"({"tabs":"strips"})").tabs, TabMode::Strips);
  EXPECT_EQ(parse_options_json(R"({"tabs":"Auto"})").tabs, TabMode::Auto);
  EXPECT_EQ(parse_options_query({{"tabs", "strips"}}).tabs, TabMode::Strips);
  EXPECT_EQ(parse_options_query({{"tabs", "none"}}).tabs, TabMode::None);
  EXPECT_EQ(parse_options_query({{"tabs", "true"}}).tabs, TabMode::Auto);
  EXPECT_EQ(error_code([] { parse_options_json(R"({"tabs":"glue"})"); }), "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"tabs":1})"); }), "invalid_option_value");
  // The canonical form names the mode; it parses back to the same options.
  JobOptions strips;
  strips.tabs = TabMode::Strips;
  EXPECT_EQ(options_to_json(strips)["tabs"], "strips");
  EXPECT_EQ(parse_options_json(options_to_json(strips).dump()).tabs, TabMode::Strips);
}

TEST(OptionsTest, UnknownOptionIsNamed) {
  std::string option;
  EXPECT_EQ(error_code(
                [] {
                  parse_options_query({{"stratgey", "QQ"}});
                },
                &option),
            "unknown_option");
  EXPECT_EQ(option, "stratgey");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"color":"red"})"); }), "unknown_option");
}

TEST(OptionsTest, BadValuesHaveStableCodes) {
  std::string option;
  EXPECT_EQ(error_code(
                [] {
                  parse_options_query({{"strategy", "FAST"}});
                },
                &option),
            "invalid_option_value");
  EXPECT_EQ(option, "strategy");
  EXPECT_EQ(error_code([] { parse_options_query({{"seed", "-3"}}); }), "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_query({{"seed", "12abc"}}); }), "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_query({{"tabs", "maybe"}}); }), "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"seed":1.5})"); }), "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"tab_room_budget":-1})"); }),
            "invalid_option_value");
  EXPECT_EQ(error_code([] {
              parse_options_query({{"tab_room_budget", "2.5"}});
            }),
            "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"strategy":3})"); }), "invalid_option_value");
  EXPECT_EQ(error_code([] {
              parse_options_query({{"seed", "1"}, {"seed", "2"}});
            }),
            "invalid_option_value");
}

// fuzz_options' finding (tests/data/fuzz): a callback URL with bytes that are not UTF-8 was
// accepted from a query string, and the job's options could then not be written as JSON (the
// service answered 500). A URL is ASCII; anything else is refused, naming the option.
TEST(OptionsTest, CallbackUrlOutsideAsciiIsRefused) {
  std::ifstream in(papernet::test::test_data_dir() + "/fuzz/options_callback_url_not_ascii.txt",
                   std::ios::binary);
  const std::string query{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string key = "callback_url=";
  ASSERT_EQ(query.rfind(key, 0), 0u) << "the finding's file is missing or changed";
  std::string option;
  EXPECT_EQ(error_code(
                [&] {
                  parse_options_query({{"callback_url", query.substr(key.size())}});
                },
                &option),
            "invalid_option_value");
  EXPECT_EQ(option, "callback_url");
  EXPECT_EQ(error_code([] {
              parse_options_query({{"callback_url", "http://127.0.0.1/caf\xC3\xA9"}});
            }),
            "invalid_option_value");
  // Percent-encoded, the same URL is taken as written.
  EXPECT_EQ(parse_options_query({{"callback_url", "http://127.0.0.1/caf%C3%A9"}}).callback_url,
            "http://127.0.0.1/caf%C3%A9");
}

TEST(OptionsTest, RangesAndLimitsAreChecked) {
  OptionsLimits limits;
  limits.max_time_limit = 30;
  limits.max_target_faces = 1000;
  std::string option;
  EXPECT_EQ(error_code(
                [&] {
                  parse_options_query({{"time_limit", "31"}}, limits);
                },
                &option),
            "option_out_of_range");
  EXPECT_EQ(option, "time_limit");
  try {  // the bound as a person writes it (it read "30.000000 seconds")
    parse_options_query({{"time_limit", "31"}}, limits);
    ADD_FAILURE() << "a time limit over the bound passed";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("at most 30 seconds"), std::string::npos) << e.what();
  }
  EXPECT_EQ(error_code([&] {
              parse_options_query({{"time_limit", "0"}}, limits);
            }),
            "option_out_of_range");
  EXPECT_EQ(error_code([&] {
              parse_options_query({{"target_faces", "1001"}}, limits);
            }),
            "option_out_of_range");
  EXPECT_EQ(error_code([&] {
              parse_options_query({{"target_faces", "3"}}, limits);
            }),
            "option_out_of_range");
  EXPECT_EQ(error_code(
                [&] {
                  parse_options_query({{"simplify", "3"}}, limits);
                },
                &option),
            "option_out_of_range");
  EXPECT_EQ(option, "detail");  // simplify N is detail N
  EXPECT_EQ(error_code([&] {
              parse_options_query({{"simplify", "1001"}}, limits);
            }),
            "option_out_of_range");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"simplify": 2.5})"); }), "invalid_option_value");
  EXPECT_EQ(error_code([] { parse_options_query({{"size_mm", "nan"}}); }), "option_out_of_range");
  EXPECT_EQ(error_code([] { parse_options_query({{"margin_mm", "-1"}}); }), "option_out_of_range");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"tab_room_budget":100000001})"); }, &option),
            "option_out_of_range");
  EXPECT_EQ(option, "tab_room_budget");
  EXPECT_EQ(parse_options_json(R"({"tab_room_budget":100000000})").tab_room_budget, 100'000'000u);
  EXPECT_EQ(error_code(
                [] {
                  parse_options_query({{"merge_budget", "100000001"}});
                },
                &option),
            "option_out_of_range");
  EXPECT_EQ(option, "merge_budget");
  EXPECT_EQ(parse_options_json(R"({"merge_budget":100000000})").merge_budget, 100'000'000u);
  EXPECT_EQ(error_code([] { parse_options_json(R"({"merge_budget":-1})"); }),
            "invalid_option_value");
  EXPECT_EQ(error_code([&] { parse_options_query({{"time_limit", "30"}}, limits); }), "");
}

TEST(OptionsTest, SizeAndScaleConflict) {
  std::string option;
  EXPECT_EQ(error_code([] { parse_options_json(R"({"size_mm":100,"scale":2})"); }, &option),
            "conflicting_options");
}

TEST(OptionsTest, MalformedJsonIsReported) {
  EXPECT_EQ(error_code([] { parse_options_json("{strategy: QQ"); }), "malformed_options");
  EXPECT_EQ(error_code([] { parse_options_json("[1,2]"); }), "malformed_options");
}

// Regression (docs/reliability.md): a value nested 200,000 deep crashed the parser's caller by
// recursion (stack overflow while printing it in the message); oversized documents are refused
// before they are parsed.
TEST(OptionsTest, DeepOrHugeDocumentsAreRefusedWithAMessage) {
  const std::string deep =
      "{\"seed\": " + std::string(200'000, '[') + std::string(200'000, ']') + "}";
  EXPECT_EQ(error_code([&] { parse_options_json(deep); }), "malformed_options");
  const std::string nested = "{\"seed\": " + std::string(8, '[') + std::string(8, ']') + "}";
  try {
    parse_options_json(nested);
    ADD_FAILURE() << "a nested array was accepted as a seed";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.code(), "invalid_option_value");
    EXPECT_LT(std::string(e.what()).size(), 200u) << e.what();
  }
  const std::string huge = "{\"strategy\": \"" + std::string(100'000, 'x') + "\"}";
  EXPECT_EQ(error_code([&] { parse_options_json(huge); }), "malformed_options");
  const std::string long_value = "{\"strategy\": \"" + std::string(10'000, 'x') + "\"}";
  try {
    parse_options_json(long_value);
    ADD_FAILURE() << "a 10,000-letter strategy was accepted";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.code(), "invalid_option_value");
    EXPECT_LT(std::string(e.what()).size(), 200u);
  }
}

TEST(OptionsTest, CanonicalJsonRoundTrips) {
  const JobOptions o = parse_options_query({{"strategy", "SEQ"},
                                            {"seed", "9"},
                                            {"scale", "3"},
                                            {"tab_room_budget", "5000"},
                                            {"merge_budget", "60000"},
                                            {"simplify", "600"}});
  const nlohmann::json doc = options_to_json(o);
  EXPECT_EQ(doc["strategy"], "SEQ");
  EXPECT_EQ(doc["detail"], 600);  // the older name is written as the newer
  EXPECT_FALSE(doc.contains("simplify"));
  EXPECT_EQ(doc["tab_room_budget"], 5000);
  EXPECT_EQ(doc["merge_budget"], 60000);
  EXPECT_TRUE(doc["size_mm"].is_null());
  const JobOptions back = parse_options_json(doc.dump());
  EXPECT_EQ(options_to_json(back), doc);
}

TEST(OptionsTest, PaperIsANamedSheetOrASizeAndABadOneIsNamed) {
  EXPECT_EQ(parse_options_query({{"paper", "a3"}}).paper, "A3");
  EXPECT_EQ(parse_options_json(R"({"paper":"420x297"})").paper, "420x297mm");
  std::string option;
  EXPECT_EQ(error_code(
                [] {
                  parse_options_query({{"paper", "B7"}});
                },
                &option),
            "invalid_option_value");
  EXPECT_EQ(option, "paper");
  // A sheet too small for its margins: the print's own check, before any geometry runs.
  EXPECT_EQ(error_code([] { parse_options_json(R"({"paper":"15x15mm"})"); }, &option),
            "option_out_of_range");
  EXPECT_EQ(option, "margin_mm");
  EXPECT_EQ(error_code([] { parse_options_json(R"({"paper":"30x30mm","margin_mm":2})"); }), "");
  // Each paper known by name is taken in any case, and the help and the OpenAPI document name it.
  const std::string help = options_help();
  const nlohmann::json api = nlohmann::json::parse(openapi_document());
  const nlohmann::json& schema = api["components"]["schemas"]["Options"]["properties"]["paper"];
  const std::string described = schema["description"];
  const std::regex pattern(schema["pattern"].get<std::string>());
  for (const Paper& p : named_papers()) {
    std::string lower = p.name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(parse_options_query({{"paper", lower}}).paper, p.name);
    EXPECT_NE(help.find(p.name), std::string::npos) << p.name;
    EXPECT_NE(described.find(p.name), std::string::npos) << p.name;
    EXPECT_TRUE(std::regex_match(p.name, pattern) && std::regex_match(lower, pattern)) << p.name;
  }
  EXPECT_FALSE(std::regex_match(std::string("A6"), pattern));
  // A size is taken in any case too: the pattern takes what the parser takes, and refuses what
  // it refuses.
  for (const std::string size : {"300x200mm", "300X200MM", "300x200", "148.5x210mm", "210X297Mm",
                                 "300x200cm", "300 x 200mm", "x200mm", "300x", "300*200mm"}) {
    bool parsed = true;
    try {
      parse_options_query({{"paper", size}});
    } catch (const InvalidOptionException&) {
      parsed = false;
    }
    EXPECT_EQ(std::regex_match(size, pattern), parsed) << size;
  }
  EXPECT_EQ(parse_options_query({{"paper", "300X200MM"}}).paper, "300x200mm");
}

// What the fit layout saves first: sheets (the default) or pieces; anything else is named.
TEST(OptionsTest, PreferIsSheetsOrPieces) {
  std::string option;
  EXPECT_EQ(JobOptions{}.prefer, FitGoal::Sheets);
  EXPECT_EQ(parse_options_query({{"prefer", "Pieces"}}).prefer, FitGoal::Pieces);
  EXPECT_EQ(parse_options_json(R"({"prefer":"sheets"})").prefer, FitGoal::Sheets);
  EXPECT_EQ(options_to_json(parse_options_json(R"({"prefer":"pieces"})"))["prefer"], "pieces");
  EXPECT_EQ(print_options(parse_options_json(R"({"prefer":"pieces"})")).prefer, FitGoal::Pieces);
  EXPECT_EQ(error_code([] { parse_options_json(R"({"prefer":"glue"})"); }, &option),
            "invalid_option_value");
  EXPECT_EQ(option, "prefer");
}

// The command line reads the same options by their flags: lengths with units, yes/no options
// alone or with a word, and a bad value names the option.
TEST(OptionsTest, CommandLineFlagsFillTheSameOptions) {
  EXPECT_EQ(option_flag("size_mm"), "--size");
  EXPECT_EQ(option_flag("min_tab_height_mm"), "--min-tab-height");
  EXPECT_EQ(option_flag("flat_fold_degrees"), "--flat-fold-degrees");
  JobOptions o;
  EXPECT_TRUE(apply_option_flag(o, "--size", "15cm"));
  EXPECT_DOUBLE_EQ(*o.size_mm, 150);
  EXPECT_TRUE(apply_option_flag(o, "--paper", "letter"));
  EXPECT_EQ(o.paper, "Letter");
  EXPECT_TRUE(apply_option_flag(o, "--margin", "0"));
  EXPECT_DOUBLE_EQ(o.margin_mm, 0);
  EXPECT_TRUE(apply_option_flag(o, "--tab-height", "4mm"));
  EXPECT_DOUBLE_EQ(o.tab_height_mm, 4);
  EXPECT_TRUE(apply_option_flag(o, "--labels", "off"));
  EXPECT_FALSE(o.labels);
  EXPECT_TRUE(is_boolean_flag("--strict"));
  EXPECT_FALSE(is_boolean_flag("--seed"));
  EXPECT_TRUE(apply_option_flag(o, "--strict", std::nullopt));
  EXPECT_TRUE(o.strict);
  EXPECT_TRUE(apply_option_flag(o, "--components", "largest"));
  EXPECT_EQ(o.components, Components::Largest);
  EXPECT_EQ(error_code([&] { apply_option_flag(o, "--components", "some"); }),
            "invalid_option_value");
  EXPECT_TRUE(apply_option_flag(o, "--strategy", "se/mp"));
  EXPECT_EQ(o.strategy, Strategy::SEMP);
  EXPECT_TRUE(apply_option_flag(o, "--tab-room-budget", "250000"));
  EXPECT_EQ(o.tab_room_budget, 250'000u);
  EXPECT_TRUE(apply_option_flag(o, "--merge-budget", "0"));
  EXPECT_EQ(o.merge_budget, 0u);
  EXPECT_FALSE(apply_option_flag(o, "--color", "red"));
  EXPECT_FALSE(apply_option_flag(o, "--size-mm", "100"));  // one name per option
  std::string option;
  EXPECT_EQ(error_code([&] { apply_option_flag(o, "--flat-fold-degrees", "lots"); }, &option),
            "invalid_option_value");
  EXPECT_EQ(option, "flat_fold_degrees");
  EXPECT_EQ(error_code([&] { apply_option_flag(o, "--size", "12 parsecs"); }, &option),
            "invalid_option_value");
  EXPECT_EQ(option, "size_mm");
  EXPECT_EQ(error_code([&] { apply_option_flag(o, "--labels", "maybe"); }), "invalid_option_value");
  for (const char* bad : {"1.5", "-1", "many"})
    EXPECT_EQ(error_code([&] { apply_option_flag(o, "--tab-room-budget", bad); }),
              "invalid_option_value")
        << bad;
  EXPECT_EQ(error_code([&] { apply_option_flag(o, "--seed", std::nullopt); }),
            "invalid_option_value");
  // Every option of the service is on the command line, and its help names it.
  const std::string help = options_help();
  const nlohmann::json all = options_to_json(JobOptions{});
  for (const auto& [name, value] : all.items())
    EXPECT_NE(help.find(option_flag(name) + " "), std::string::npos) << name;
}

// The OpenAPI document lists exactly the options the parsers take, as query parameters and in
// the JSON part's schema, so that a client generated from it never sends a refused name.
TEST(OptionsTest, OpenApiListsEveryOption) {
  const nlohmann::json api = nlohmann::json::parse(openapi_document());
  std::set<std::string> query, schema, options;
  for (const auto& p : api["paths"]["/v1/jobs"]["post"]["parameters"])
    if (p["in"] == "query" && p["name"] != "format" && !p.value("deprecated", false))
      query.insert(p["name"].get<std::string>());
  for (const auto& [name, value] : api["components"]["schemas"]["Options"]["properties"].items())
    if (!value.value("deprecated", false)) schema.insert(name);
  const nlohmann::json all = options_to_json(JobOptions{});
  for (const auto& [name, value] : all.items()) options.insert(name);
  EXPECT_EQ(query, options);
  EXPECT_EQ(schema, options);
}

// The kit's title: text of at most 80 characters (UTF-8, so 80 two-byte letters too), its end
// spaces dropped, the same from a query, a JSON part and the command line; control characters,
// bytes that are not UTF-8 and longer titles are refused naming the option.
TEST(OptionsTest, TheTitleIsShortTextWithoutControlCharacters) {
  EXPECT_EQ(parse_options_query({}).title, "");
  EXPECT_TRUE(options_to_json(parse_options_query({}))["title"].is_null());
  EXPECT_EQ(parse_options_query({{"title", "  Kitchen Duck "}}).title, "Kitchen Duck");
  EXPECT_EQ(parse_options_json(R"({"title":"Ente \u00b7 Kit"})").title, "Ente \u00b7 Kit");
  EXPECT_EQ(options_to_json(parse_options_query({{"title", "Duck"}}))["title"], "Duck");
  JobOptions cli;
  EXPECT_TRUE(apply_option_flag(cli, "--title", "Duck"));
  EXPECT_EQ(cli.title, "Duck");
  std::string e80;  // 80 letters of two bytes each
  for (int i = 0; i < 80; ++i) e80 += "\u00e9";
  EXPECT_EQ(parse_options_query({{"title", e80}}).title, e80);
  std::string option;
  EXPECT_EQ(error_code(
                [&] {
                  parse_options_query({{"title", e80 + "x"}});
                },
                &option),
            "option_out_of_range");
  EXPECT_EQ(option, "title");
  for (const std::string& bad :
       {std::string("Duck\nKit"), std::string("Duck\tKit"), std::string("Duck\x7f"),
        std::string("Duck\xc2\x85"), std::string("Duck\xff"), std::string("Duck\xc3")}) {
    option.clear();
    EXPECT_EQ(error_code(
                  [&] {
                    parse_options_query({{"title", bad}});
                  },
                  &option),
              "invalid_option_value")
        << bad;
    EXPECT_EQ(option, "title");
  }
  EXPECT_EQ(error_code([] { parse_options_json(R"({"title":12})"); }), "invalid_option_value");
}
