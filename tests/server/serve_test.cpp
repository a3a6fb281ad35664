// End-to-end: starts the real `papernet serve` on a free loopback port and speaks HTTP to it.
#include <gtest/gtest.h>

#include <cstdint>
#include <set>

#include "api/net_json.h"
#include "core/unfold/net_check.h"
#include "tests/support/files.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"
#include "tests/support/postgres.h"
#include "tests/support/sanitized.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using namespace papernet::test;

// The end-to-end tests run against both stores.
class ServeTest : public BothStores {};
INSTANTIATE_BOTH_STORES(ServeTest);

namespace {

// Three triangles on one edge: loads fine, cannot be unfolded (non-manifold edge).
constexpr const char* kNonManifoldObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";

}  // namespace

TEST_P(ServeTest, HealthReadinessMetricsAndOpenApi) {
  Server s({"--workers", "1"});
  auto c = s.client();
  EXPECT_EQ(c.Get("/healthz")->status, 200);
  EXPECT_EQ(c.Get("/readyz")->status, 200);
  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("papernet_queue_length 0"), std::string::npos);
  EXPECT_NE(metrics->body.find("papernet_http_requests_total{status=\"200\"}"), std::string::npos);
  auto api = c.Get("/v1/openapi.json");
  ASSERT_TRUE(api);
  const json doc = json::parse(api->body);
  EXPECT_EQ(doc["openapi"].get<std::string>().substr(0, 2), "3.");
  EXPECT_TRUE(doc["paths"].contains("/v1/jobs/{id}"));
  EXPECT_TRUE(doc["paths"].contains("/v1/jobs/{id}/pages/{k}"));
}

TEST_P(ServeTest, SubmitPollAndFetchObj) {
  Server s({"--workers", "1"});
  const std::string id = submit(s, test_mesh("sample.obj"), "model/obj",
                                "?detail=full&strategy=TU&seed=3" + kLightQuery);
  const json job = wait_final(s, id);
  EXPECT_EQ(job["options"]["strategy"], "TU");
  EXPECT_EQ(job["input"]["format"], "obj");
  ASSERT_EQ(job["status"], "succeeded") << job.dump();
  auto c = s.client();
  auto net = c.Get("/v1/jobs/" + id + "/net.json");
  ASSERT_EQ(net->status, 200);
  const json doc = json::parse(net->body);
  EXPECT_EQ(doc["format"], "papernet.net/2");
  EXPECT_EQ(doc["metrics"]["overlaps"], 0);
  EXPECT_EQ(doc["net"]["faces"].size(), doc["mesh"]["faces"].size());
  const papernet::NetDocument net_doc = papernet::read_net_json(net->body);
  // Printed with layout fit, the net is cut into pieces that each fit a sheet.
  const papernet::NetCheckReport check =
      papernet::check_pieces(net_doc.mesh, net_doc.net, net_doc.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  EXPECT_EQ(net->get_header_value("X-Papernet-Level"), "complete; faces=1000; input-faces=1000");

  // The same mesh with the same options is answered from the stored result at once.
  auto again = c.Post("/v1/jobs?detail=full&strategy=TU&seed=3" + kLightQuery,
                      test_mesh("sample.obj"), "model/obj");
  ASSERT_EQ(again->status, 202);
  EXPECT_EQ(body(again)["status"], "succeeded");
  EXPECT_EQ(body(again)["result"]["metrics"]["reused_from"], id);
  EXPECT_EQ(c.Get("/v1/jobs/" + body(again)["id"].get<std::string>() + "/net.json")->body,
            net->body);
  auto svg = c.Get("/v1/jobs/" + id + "/net.svg");
  ASSERT_EQ(svg->status, 200);
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  auto pdf = c.Get("/v1/jobs/" + id + "/net.pdf");
  ASSERT_EQ(pdf->status, 200);
  EXPECT_EQ(pdf->body.substr(0, 5), "%PDF-");
  auto glb = c.Get("/v1/jobs/" + id + "/mesh.glb");
  ASSERT_EQ(glb->status, 200);
  EXPECT_EQ(glb->body.substr(0, 4), "glTF");
}

namespace {

// The value of attribute data-NAME in an SVG document ("" when absent).
std::string svg_data(const std::string& svg, const std::string& name) {
  const std::string key = "data-" + name + "=\"";
  const auto at = svg.find(key);
  if (at == std::string::npos) return "";
  const auto from = at + key.size();
  return svg.substr(from, svg.find('"', from) - from);
}

}  // namespace

// The `tabs` option takes a mode (auto, strips, none) or, as first, a boolean.
TEST_P(ServeTest, TabsOptionTakesModesOrABoolean) {
  Server s({"--workers", "1"});
  auto c = s.client();
  // Tiled, the print is the unfolder's net whole (a fit layout may print pieces grown anew,
  // whose own cuts leave room for tabs: docs/print.md, "Fit layout"), and the job is seconds
  // shorter: the fit search is not what this test is about.
  const std::string strips =
      submit(s, test_mesh("sample.obj"), "model/obj",
             "?detail=full&strategy=TU&seed=3&layout=tile&tabs=strips" + kLightQuery);
  const std::string yes =
      submit(s, test_mesh("sample.obj"), "model/obj",
             "?detail=full&strategy=TU&seed=3&layout=tile&tabs=true" + kLightQuery);
  const json a = wait_final(s, strips), b = wait_final(s, yes);
  ASSERT_EQ(a["status"], "succeeded") << a.dump();
  ASSERT_EQ(b["status"], "succeeded") << b.dump();
  EXPECT_EQ(a["options"]["tabs"], "strips");
  EXPECT_EQ(b["options"]["tabs"], "auto");
  const std::string svg_a = c.Get("/v1/jobs/" + strips + "/net.svg")->body;
  const std::string svg_b = c.Get("/v1/jobs/" + yes + "/net.svg")->body;
  ASSERT_NE(svg_data(svg_a, "cut-edges"), "");
  EXPECT_EQ(svg_data(svg_a, "tabs"), "0");
  EXPECT_EQ(svg_data(svg_a, "strips"), svg_data(svg_a, "cut-edges"));
  // auto: tabs on the net, after the cuts were changed to make room for them (docs/tabs.md),
  // and the delivered net JSON is that net, valid.
  EXPECT_GT(std::stoi(svg_data(svg_b, "tabs")), 4 * std::stoi(svg_data(svg_b, "strips")));
  const papernet::NetDocument doc =
      papernet::read_net_json(c.Get("/v1/jobs/" + yes + "/net.json")->body);
  EXPECT_TRUE(papernet::check_pieces(doc.mesh, doc.net, doc.piece).ok());
  expect_problem(c.Post("/v1/jobs?tabs=glue", test_mesh("sample.obj"), "model/obj"), 400,
                 "invalid_option_value");

  // tab_room_budget=0: the unfolder's net as it is, with more strips.
  const std::string unchanged =
      submit(s, test_mesh("sample.obj"), "model/obj",
             "?detail=full&strategy=TU&seed=3&layout=tile&tab_room_budget=0");
  const json u = wait_final(s, unchanged);
  ASSERT_EQ(u["status"], "succeeded") << u.dump();
  EXPECT_EQ(u["options"]["tab_room_budget"], 0);
  EXPECT_EQ(b["options"]["tab_room_budget"], light_tab_room(100'000));
  EXPECT_EQ(b["options"]["merge_budget"], light_merge(480'000));
  const std::string svg_u = c.Get("/v1/jobs/" + unchanged + "/net.svg")->body;
  EXPECT_GT(std::stoi(svg_data(svg_u, "strips")), 2 * std::stoi(svg_data(svg_b, "strips")));
  expect_problem(c.Post("/v1/jobs?tab_room_budget=-5", test_mesh("sample.obj"), "model/obj"), 400,
                 "invalid_option_value");
}

// Progressive unfolding (the default, AUTO, starts with QQ): while the job runs, the result URLs
// serve the latest overlap-free intermediate, said so in a header and in the body; then the
// complete net.
TEST_P(ServeTest, ProgressiveJobServesIntermediatesThenTheResult) {
  Server s({"--workers", "1"});
  // No tab-room pass: this is about the unfolding's intermediates, and on a loaded machine the
  // pass alone can take a minute after them.
  const std::string id = submit(s, test_mesh("Duck.glb"), "model/gltf-binary",
                                "?detail=full&tab_room_budget=0&colour=none");
  auto c = s.client();
  bool intermediate = false, not_ready = false;
  // A deadline rather than a count of polls: on a loaded machine (CI runs this beside the other
  // tests) the collapse and the coarse unfolding may take many seconds.
  const auto end = std::chrono::steady_clock::now() + 120s;
  while (!intermediate && std::chrono::steady_clock::now() < end) {
    auto res = c.Get("/v1/jobs/" + id + "/net.json");
    ASSERT_TRUE(res);
    if (res->status == 409) {
      not_ready = true;
      EXPECT_EQ(json::parse(res->body)["code"], "result_not_ready");
      EXPECT_FALSE(res->get_header_value("Retry-After").empty());
    } else if (res->get_header_value("X-Papernet-Level").rfind("intermediate", 0) == 0) {
      intermediate = true;
      const json doc = json::parse(res->body);
      EXPECT_EQ(doc["level"]["kind"], "intermediate");
      EXPECT_LT(doc["mesh"]["faces"].size(), 4212u);
      const papernet::NetDocument net = papernet::read_net_json(res->body);
      EXPECT_TRUE(papernet::check_pieces(net.mesh, net.net, net.piece).ok())
          << "intermediate nets are valid";
      EXPECT_EQ(c.Get("/v1/jobs/" + id + "/net.svg")->status, 200);
      EXPECT_NE(body(c.Get("/v1/jobs/" + id))["links"].value("net.json", ""), "");
    } else {
      break;  // finished before we saw an intermediate
    }
    std::this_thread::sleep_for(2ms);
  }
  EXPECT_TRUE(not_ready || intermediate);
  EXPECT_TRUE(intermediate) << "no intermediate was served while the job ran";
  const json job = wait_final(s, id, 180);  // the job's own limit is 120 s
  ASSERT_TRUE(job["status"] == "succeeded" || job["status"] == "approximated") << job.dump();
  EXPECT_EQ(job["options"]["strategy"], "AUTO");
  auto net = c.Get("/v1/jobs/" + id + "/net.json");
  ASSERT_EQ(net->status, 200);
  const json doc = json::parse(net->body);
  EXPECT_EQ(doc["result"], job["result"]["kind"]);
  EXPECT_FALSE(doc.contains("level"));
  EXPECT_EQ(net->get_header_value("X-Papernet-Level").rfind(job["result"]["kind"], 0), 0u);
}

// A time limit too short to finish the uncollapse gives the last overlap-free approximation.
// (QQ completes the Duck's 4,212 faces in ~0.4 s since TU's walks towards overlapping faces, so
// 0.1 s. On a loaded machine 0.1 s may not even unfold the coarse mesh: then the net is of the
// coarsest mesh the collapses reach, still an approximation.)
TEST_P(ServeTest, ShortTimeLimitGivesAnApproximateNet) {
  Server s({"--workers", "1"});
  const json job = wait_final(s, submit(s, test_mesh("Duck.glb"), "model/gltf-binary",
                                        "?detail=full&time_limit=0.1&colour=none"));
  ASSERT_EQ(job["status"], "approximated") << job.dump();
  EXPECT_EQ(job["result"]["kind"], "approximate");
  EXPECT_LT(job["result"]["faces"].get<int>(), 4212);
  EXPECT_EQ(job["result"]["input_faces"], 4212);
  auto net = s.client().Get("/v1/jobs/" + job["id"].get<std::string>() + "/net.json");
  const json doc = json::parse(net->body);
  EXPECT_EQ(doc["result"], "approximate");
  EXPECT_GT(doc["metrics"]["hausdorff"].get<double>(), 0);
  EXPECT_EQ(net->get_header_value("X-Papernet-Level").rfind("approximate", 0), 0u);
}

TEST_P(ServeTest, SubmitGlbDracoAndMultipartGltf) {
  Server s({"--workers", "1"});
  std::vector<std::string> ids = {
      submit(s, test_mesh("testplate.glb"), "model/gltf-binary",
             "?strategy=TU&detail=full" + kLightQuery),
      // Without colour: the textured box prints 12 sheets of colour at 200 mm (seconds each),
      // and reading the formats is what is tested here.
      submit(s, test_mesh("Box_Draco.glb"), "", "?strategy=TU&colour=none" + kLightQuery)};
  httplib::MultipartFormDataItems items = {
      {"mesh", test_mesh("gltf_external/Box.gltf"), "Box.gltf", "model/gltf+json"},
      {"buffers", test_mesh("gltf_external/Box0.bin"), "Box0.bin", "application/octet-stream"},
      {"options", R"({"strategy":"TU","seed":5,"colour":"none"})", "", "application/json"}};
  auto res = s.client().Post("/v1/jobs", items);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 202) << res->body;
  EXPECT_EQ(body(res)["input"]["format"], "gltf");
  EXPECT_EQ(body(res)["options"]["seed"], 5);
  ids.push_back(body(res)["id"]);
  for (const std::string& id : ids) {
    const json job = wait_final(s, id);
    EXPECT_EQ(job["status"], "succeeded") << job.dump();
    EXPECT_GT(job["input"]["faces"].get<int>(), 0) << job.dump();
    auto net = s.client().Get("/v1/jobs/" + id + "/net.json");
    ASSERT_TRUE(net);
    ASSERT_EQ(net->status, 200);
    EXPECT_EQ(json::parse(net->body)["net"]["faces"].size(), job["result"]["faces"]);
  }
  // The .gltf without its buffer part cannot be read: the job says so.
  httplib::MultipartFormDataItems no_buffer = {
      {"mesh", test_mesh("gltf_external/Box.gltf"), "Box.gltf", "model/gltf+json"}};
  const std::string missing = body(s.client().Post("/v1/jobs", no_buffer))["id"];
  const json failed = wait_final(s, missing);
  EXPECT_EQ(failed["error"]["code"], "unreadable_mesh") << failed.dump();
  EXPECT_NE(failed["error"]["detail"].get<std::string>().find("Box0.bin"), std::string::npos)
      << failed.dump();
}

TEST_P(ServeTest, ServesTheTexturesBesideTheNet) {
  Server s({"--workers", "1"});
  auto c = s.client();
  const std::string box =
      submit(s, test_mesh("BoxTextured.glb"), "model/gltf-binary", "?strategy=TU&size_mm=80");
  // A .gltf with its buffer and its image uploaded as parts, and once without the image. Tiled:
  // the fit layout of its 3,624 faces took most of this test's minutes under the sanitizers.
  const std::string truck = "CesiumMilkTruck/CesiumMilkTruck";
  httplib::MultipartFormDataItems items = {
      {"mesh", test_mesh(truck + ".gltf"), "CesiumMilkTruck.gltf", "model/gltf+json"},
      {"buffers", test_mesh(truck + "0.bin"), "CesiumMilkTruck0.bin", "application/octet-stream"},
      {"buffers", test_mesh(truck + ".png"), "CesiumMilkTruck.png", "image/png"},
      {"options",
       R"({"strategy":"TU","tab_room_budget":0,"detail":"full","colour":"none","layout":"tile"})",
       "", "application/json"}};
  const std::string with_image = body(c.Post("/v1/jobs", items))["id"];
  items.erase(items.begin() + 2);
  const std::string without_image = body(c.Post("/v1/jobs", items))["id"];

  const json job = wait_final(s, box);
  ASSERT_EQ(job["status"], "succeeded") << job.dump();
  EXPECT_EQ(job["links"]["textures"], json::array({"/v1/jobs/" + box + "/textures/0"}));
  auto net = c.Get("/v1/jobs/" + box + "/net.json");
  ASSERT_EQ(net->status, 200);
  const json doc = json::parse(net->body);
  EXPECT_EQ(doc["mesh"]["uvs"].size(), doc["mesh"]["faces"].size());
  ASSERT_EQ(doc["textures"].size(), 1u);
  const papernet::NetDocument net_doc = papernet::read_net_json(net->body);
  EXPECT_TRUE(papernet::check_pieces(net_doc.mesh, net_doc.net, net_doc.piece).ok());
  auto texture = c.Get("/v1/jobs/" + box + "/textures/0");
  ASSERT_EQ(texture->status, 200);
  EXPECT_EQ(texture->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(texture->body.substr(0, 8), "\x89PNG\r\n\x1a\n");
  expect_problem(c.Get("/v1/jobs/" + box + "/textures/1"), 404, "not_found");

  const json truck_job = wait_final(s, with_image, 180);
  ASSERT_EQ(truck_job["status"], "succeeded") << truck_job.dump();
  auto truck_texture = c.Get("/v1/jobs/" + with_image + "/textures/0");
  ASSERT_EQ(truck_texture->status, 200);
  EXPECT_EQ(truck_texture->body, test_mesh(truck + ".png"));
  // Without its image the model still unfolds; the result says the texture was not used.
  const json bare = wait_final(s, without_image, 180);
  ASSERT_EQ(bare["status"], "succeeded") << bare.dump();
  bool said = false;
  for (const json& r : bare["result"]["repairs"]) said |= r["code"] == "texture_not_used";
  EXPECT_TRUE(said) << bare["result"]["repairs"].dump();
  EXPECT_FALSE(bare["links"].contains("textures"));
  expect_problem(c.Get("/v1/jobs/" + without_image + "/textures/0"), 404, "not_found");
}

// Each printed page on its own, at /v1/jobs/{id}/pages/{k} (k from 1, as the page numbers
// itself) and listed in links.pages; the net JSON's placements name those pages from 0; the
// whole net stays at net.svg.
TEST_P(ServeTest, ServesEachPrintedPageOnItsOwn) {
  Server s({"--workers", "1"});
  const std::string id = submit(s, test_mesh("testplate.glb"), "model/gltf-binary",
                                "?strategy=TU&detail=full&title=Test%20plate");
  const json job = wait_final(s, id);
  ASSERT_EQ(job["status"], "succeeded") << job.dump();
  auto c = s.client();
  auto net = c.Get("/v1/jobs/" + id + "/net.json");
  EXPECT_EQ(net->get_header_value("Content-Disposition"), "inline; filename=\"Test plate.json\"");
  ASSERT_EQ(net->status, 200);
  const json doc = json::parse(net->body);
  ASSERT_TRUE(doc.contains("print")) << net->body.substr(0, 200);
  const int n = doc["print"]["pages"];
  ASSERT_GT(n, 1);
  EXPECT_EQ(job["result"]["metrics"]["pages"], n);
  ASSERT_EQ(job["links"]["pages"].size(), static_cast<std::size_t>(n)) << job["links"].dump();
  for (int k = 1; k <= n; ++k) {
    const std::string path = "/v1/jobs/" + id + "/pages/" + std::to_string(k);
    EXPECT_EQ(job["links"]["pages"][k - 1], path);
    auto page = c.Get(path);
    ASSERT_EQ(page->status, 200) << path;
    EXPECT_EQ(page->get_header_value("Content-Type"), "image/svg+xml");
    // Saved from a browser or by curl -OJ, the page is named, with its extension.
    EXPECT_EQ(page->get_header_value("Content-Disposition"),
              "inline; filename=\"Test plate - page " + std::to_string(k) + ".svg\"");
    EXPECT_NE(page->body.find("page " + std::to_string(k) + " of " + std::to_string(n)),
              std::string::npos)
        << path;
  }
  for (const json& placed : doc["print"]["placements"]) {
    EXPECT_GE(placed["page"], 0);
    EXPECT_LT(placed["page"], n);
  }
  expect_problem(c.Get("/v1/jobs/" + id + "/pages/0"), 404, "not_found");
  expect_problem(c.Get("/v1/jobs/" + id + "/pages/" + std::to_string(n + 1)), 404, "not_found");
  auto svg = c.Get("/v1/jobs/" + id + "/net.svg");
  ASSERT_EQ(svg->status, 200);
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  EXPECT_NE(svg->body.find("<title>Test plate</title>"), std::string::npos) << "the whole net's";
}

namespace {

using papernet::test::base64;

// A PNG chunk: length, type, data, CRC (computed here).
std::string png_chunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  std::uint32_t crc = 0xffffffff;
  for (char c : body) {
    crc ^= std::uint8_t(c);
    for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1)));
  }
  crc ^= 0xffffffff;
  std::string out;
  for (int shift = 24; shift >= 0; shift -= 8) out += char((data.size() >> shift) & 0xff);
  out += body;
  for (int shift = 24; shift >= 0; shift -= 8) out += char((crc >> shift) & 0xff);
  return out;
}

// A PNG that declares `side` x `side` pixels (8-bit RGBA) and holds no image data.
std::string png_header(std::uint32_t side) {
  std::string ihdr;
  for (int k = 0; k < 2; ++k)
    for (int shift = 24; shift >= 0; shift -= 8) ihdr += char((side >> shift) & 0xff);
  ihdr += std::string("\x08\x06\x00\x00\x00", 5);
  std::string png = "\x89PNG\r\n\x1a\n";
  png += png_chunk("IHDR", ihdr);
  png += png_chunk("IDAT", "");
  return png;
}

// A textured triangle (.gltf, data URIs only) whose image is `png`.
std::string textured_triangle(const std::string& png) {
  const float data[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
  const std::string buffer(reinterpret_cast<const char*>(data), sizeof data);
  return json{
      {"asset", {{"version", "2.0"}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", "data:image/png;base64," + base64(png)}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
      {"buffers",
       {{{"uri", "data:application/octet-stream;base64," + base64(buffer)}, {"byteLength", 60}}}}}
      .dump();
}

}  // namespace

TEST_P(ServeTest, AnImageOverThePixelLimitIs413) {
  Server s({"--workers", "1"});
  const std::string big =
      submit(s, textured_triangle(png_header(20000)), "model/gltf+json", "?strategy=TU");
  const json job = wait_final(s, big);
  EXPECT_EQ(job["status"], "failed") << job.dump();
  EXPECT_EQ(job["error"]["code"], "image_too_large") << job.dump();
  expect_problem(s.client().Get("/v1/jobs/" + big + "/net.json"), 413, "image_too_large");
  // A header alone, under the limit, is no image: the net comes with texture_not_used.
  const json small = wait_final(
      s, submit(s, textured_triangle(png_header(64)), "model/gltf+json", "?strategy=TU"));
  ASSERT_EQ(small["status"], "succeeded") << small.dump();
  bool said = false;
  for (const json& r : small["result"]["repairs"]) said |= r["code"] == "texture_not_used";
  EXPECT_TRUE(said) << small.dump();
}

TEST_P(ServeTest, EventStreamEndsWithTheFinalState) {
  Server s({"--workers", "1"});
  // Tiled: the stream is what this test is about, not the fit search.
  const std::string id = submit(s, test_mesh("sample.obj"), "model/obj",
                                "?detail=full&strategy=TU&layout=tile" + kLightQuery);
  std::string stream;
  auto res = s.client().Get("/v1/jobs/" + id + "/events", [&](const char* data, size_t n) {
    stream.append(data, n);
    return true;
  });
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/event-stream");
  const auto done = stream.rfind("event: done\ndata: ");
  ASSERT_NE(done, std::string::npos) << stream;
  const std::string data = stream.substr(done + 18, stream.find('\n', done + 18) - done - 18);
  const json last = json::parse(data);
  EXPECT_EQ(last["id"], id);
  EXPECT_EQ(last, wait_final(s, id)) << "the last event is the job's final state";
  EXPECT_NE(stream.find("event: progress"), std::string::npos) << stream;
  // The stream sends the state as it is when it looks (changes are coalesced, at most ten a
  // second), so a short phase may pass unseen; the tab-room pass takes most of this job.
  EXPECT_TRUE(stream.find("\"phase\":\"unfold\"") != std::string::npos ||
              stream.find("\"phase\":\"tabs\"") != std::string::npos)
      << "the stream shows the job's progress while it runs\n"
      << stream;
}

TEST_P(ServeTest, EveryErrorCodeFromTheInputThatCausesIt) {
  Server s({"--workers", "1", "--max-body-bytes", "100000", "--max-faces", "500"});
  auto c = s.client();
  const std::string obj = test_mesh("sample.obj");  // 1000 faces, 81 KB
  expect_problem(c.Post("/v1/jobs?detail=full&strategy=FAST", obj, "model/obj"), 400,
                 "invalid_option_value");
  expect_problem(c.Post("/v1/jobs?color=red", obj, "model/obj"), 400, "unknown_option");
  expect_problem(c.Post("/v1/jobs?time_limit=100000", obj, "model/obj"), 400,
                 "option_out_of_range");
  expect_problem(c.Get("/v1/jobs/0123456789abcdef0123456789abcdef"), 404, "job_not_found");
  expect_problem(c.Get("/v1/jobs/not-a-job-id"), 404, "job_not_found");
  expect_problem(c.Get("/v1/jobs/..%2F..%2Fetc%2Fpasswd/net.json"), 404, "not_found");
  expect_problem(c.Get("/v1/nothing"), 404, "not_found");
  expect_problem(c.Post("/v1/jobs", std::string(150000, 'v'), "model/obj"), 413,
                 "payload_too_large");
  expect_problem(c.Post("/v1/jobs", "\x89PNG\r\n", "image/png"), 415, "unsupported_format");
  expect_problem(c.Post("/v1/jobs", "hello\nworld\n", "application/octet-stream"), 415,
                 "unsupported_format");

  // Faults found by a worker fail the job; its result answers with the problem.
  const std::string too_big = submit(s, obj, "model/obj");
  EXPECT_EQ(wait_final(s, too_big)["error"]["code"], "too_many_faces");
  expect_problem(c.Get("/v1/jobs/" + too_big + "/net.json"), 413, "too_many_faces");

  // A mesh strict refuses; repair cuts its non-manifold edge instead.
  const std::string bad = submit(s, kNonManifoldObj, "model/obj", "?strict=true");
  const json failed = wait_final(s, bad);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"]["code"], "invalid_mesh");
  EXPECT_FALSE(failed["error"]["reasons"].empty()) << failed.dump();
  const json repaired = wait_final(s, submit(s, kNonManifoldObj, "model/obj"));
  EXPECT_EQ(repaired["status"], "succeeded") << repaired.dump();
  EXPECT_EQ(repaired["result"]["repairs"][0]["code"], "cut_non_manifold_edges");
  // Nothing to unfold, repair or not.
  const json points = wait_final(s, submit(s, "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "model/obj"));
  EXPECT_EQ(points["error"]["code"], "invalid_mesh");
  EXPECT_NE(points["error"]["detail"].get<std::string>().find("no faces"), std::string::npos);
  expect_problem(c.Get("/v1/jobs/" + bad + "/net.svg"), 422, "invalid_mesh");
  expect_problem(c.Delete("/v1/jobs/" + bad), 409, "job_finished");
}

TEST_P(ServeTest, ListsRecentJobsPaged) {
  Server s({"--workers", "1"});
  std::vector<std::string> ids;
  for (int i = 0; i < 3; ++i)
    ids.push_back(submit(s, kNonManifoldObj + std::string(i, '\n'), "model/obj"));
  auto page = body(s.client().Get("/v1/jobs?limit=2"));
  ASSERT_EQ(page["jobs"].size(), 2u);
  EXPECT_EQ(page["jobs"][0]["id"], ids[2]);
  EXPECT_EQ(page["jobs"][1]["id"], ids[1]);
  ASSERT_TRUE(page["next"].is_string());
  auto next = body(s.client().Get(page["next"].get<std::string>()));
  ASSERT_EQ(next["jobs"].size(), 1u);
  EXPECT_EQ(next["jobs"][0]["id"], ids[0]);
  expect_problem(s.client().Get("/v1/jobs?limit=0"), 400, "malformed_request");
}

// Needs jobs that take a while: a full queue, cancelling a running job, a graceful stop.
TEST_P(ServeTest, QueueFullCancelAndShutdown) {
  Server s({"--workers", "1", "--queue-length", "1", "--shutdown-grace", "30"});
  const std::string mesh = test_mesh("reference.obj");
  const std::string first = submit(s, mesh, "model/obj", "?detail=full&strategy=TU&time_limit=60");
  std::this_thread::sleep_for(300ms);
  const json probe = body(s.client().Get("/v1/jobs/" + first));
  ASSERT_EQ(probe["status"], "running") << "the test needs a job that runs for a while";
  const std::string queued = submit(s, mesh, "model/obj", "?strategy=TU&seed=2");
  auto full = s.client().Post("/v1/jobs?seed=3", mesh, "model/obj");
  expect_problem(full, 429, "queue_full");
  EXPECT_FALSE(full->get_header_value("Retry-After").empty());
  EXPECT_EQ(body(s.client().Get("/v1/jobs/" + queued))["progress"]["queue_position"], 1);

  EXPECT_EQ(s.client().Delete("/v1/jobs/" + queued)->status, 202);
  EXPECT_EQ(wait_final(s, queued)["status"], "cancelled");
  // Cancelled is final: a second cancel is a conflict, as for any finished job.
  expect_problem(s.client().Delete("/v1/jobs/" + queued), 409, "job_finished");
  const auto before = std::chrono::steady_clock::now();
  EXPECT_EQ(s.client().Delete("/v1/jobs/" + first)->status, 202);
  EXPECT_EQ(wait_final(s, first)["status"], "cancelled");
  EXPECT_LT(std::chrono::steady_clock::now() - before, 1500ms);
  expect_problem(s.client().Get("/v1/jobs/" + first + "/net.json"), 410, "job_cancelled");

  // Graceful stop: while the running job has its grace period, no new work is accepted.
  const std::string running = submit(s, mesh, "model/obj", "?strategy=TU&seed=4");
  std::this_thread::sleep_for(300ms);
  s.signal(SIGTERM);
  std::this_thread::sleep_for(200ms);
  expect_problem(s.client().Post("/v1/jobs", mesh, "model/obj"), 503, "shutting_down");
  expect_problem(s.client().Get("/readyz"), 503, "shutting_down");
}

// The pages of a coloured print take seconds (the Duck: several pages, here at 600 dpi); a cancel
// stops the job between pages rather than after the last. Tiled: the pages are the same work, and
// the fit search before them is not what this test is about (20 s of its 34 under ASan).
TEST_P(ServeTest, CancellingWhileThePagesAreWrittenStopsThePrint) {
  Server s({});
  const std::string id =
      submit(s, test_mesh("Duck.glb"), "", "?colour=auto&dpi=600&layout=tile" + kLightQuery);
  wait_phase(s, id, "write");
  EXPECT_EQ(s.client().Delete("/v1/jobs/" + id)->status, 202);
  const json job = wait_final(s, id);
  EXPECT_EQ(job["status"], "cancelled") << job.dump();
  expect_problem(s.client().Get("/v1/jobs/" + id + "/net.json"), 410, "job_cancelled");
}

// SIGTERM with no grace: the running job is stopped, stays queued, and runs after a restart.
TEST_P(ServeTest, GracefulStopKeepsTheRunningJobForTheNextStart) {
  auto server = std::make_unique<Server>(std::vector<std::string>{"--shutdown-grace", "0"});
  const fs::path data = server->data();
  const std::string id =
      submit(*server, test_mesh("Duck.glb"), "", "?detail=full&strategy=TU&colour=none");
  wait_running(*server, id);
  server->keep_data();
  const int status = server->stop(SIGTERM);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  server.reset();
  Server restarted({}, data);
  const json job = wait_final(restarted, id);
  EXPECT_TRUE(job["status"] == "succeeded" || job["status"] == "approximated") << job.dump();
  EXPECT_NE(restarted.log().find("running -> queued (server stopping)"), std::string::npos)
      << restarted.log();
}

// kill -9 with jobs queued and running; a restart finishes every one and loses no result.
TEST_P(ServeTest, KillNineThenRestartFinishesEveryJob) {
  auto server = std::make_unique<Server>(std::vector<std::string>{"--workers", "1"});
  const fs::path data = server->data();
  const std::string finished = submit(*server, test_mesh("mirror.ply"), "", "?strategy=TU");
  const json done_before = wait_final(*server, finished);
  ASSERT_EQ(done_before["status"], "succeeded") << done_before.dump();
  const std::string net_before = server->client().Get("/v1/jobs/" + finished + "/net.json")->body;

  std::vector<std::string> ids = {finished};
  for (const char* name : {"Duck.glb", "testplate.glb", "Box_Draco.glb"})
    ids.push_back(submit(*server, test_mesh(name), "", "?detail=full&strategy=TU&colour=none"));
  wait_running(*server, ids[1]);
  EXPECT_EQ(body(server->client().Get("/v1/jobs/" + ids[3]))["status"], "queued");
  server->keep_data();
  EXPECT_TRUE(WIFSIGNALED(server->stop(SIGKILL)));
  server.reset();

  Server restarted({"--workers", "1"}, data);
  for (const std::string& id : ids) {
    const json job = wait_final(restarted, id);
    EXPECT_EQ(job["status"], "succeeded") << job.dump();
    auto net = restarted.client().Get("/v1/jobs/" + id + "/net.json");
    ASSERT_TRUE(net);
    EXPECT_EQ(net->status, 200);
  }
  EXPECT_EQ(body(restarted.client().Get("/v1/jobs/" + ids[1]))["result"]["metrics"]["faces"], 4212);
  EXPECT_EQ(restarted.client().Get("/v1/jobs/" + finished + "/net.json")->body, net_before);
}

// The command line and the service run one pipeline (engine/pipeline.h): the same mesh and
// options give the same net JSON, its seconds aside, for a progressive, a TU and a simplified job.
TEST_P(ServeTest, CommandLineAndServiceWriteTheSameNet) {
  Server s({"--workers", "1"});
  const std::string mesh = test_mesh("mirror.ply");  // 286 faces
  struct Job {
    std::string query, flags, status;
  };
  const Job jobs[] = {
      {"detail=full&strategy=QQ&seed=2&size_mm=150",
       "--detail full --strategy QQ --seed 2 --size 150mm", "succeeded"},
      {"detail=full&strategy=TU&seed=3&paper=none",
       "--detail full --strategy TU --seed 3 --paper none", "succeeded"},
      // detail auto: at 60 mm the mirror's 286 faces are more than a person can build (100)
      {"strategy=TU&seed=3&size_mm=60", "--strategy TU --seed 3 --size 60mm", "approximated"},
      {"simplify=60&seed=1&tabs=strips", "--simplify 60 --seed 1 --tabs strips", "approximated"},
  };
  const auto without_seconds = [](json doc) {
    doc["metrics"].erase("seconds");
    return doc;
  };
  const fs::path out =
      fs::temp_directory_path() / ("papernet-same-net-" + std::to_string(getpid()) + ".json");
  // The service prints every job: the command line prints too (a PDF), so that its net JSON
  // has the same pieces as printed and the same `print`.
  fs::path pdf = out;
  pdf.replace_extension(".pdf");
  for (const auto& [query, flags, status] : jobs) {
    SCOPED_TRACE(query);
    const std::string id = submit(s, mesh, "model/x-ply", "?" + query);
    ASSERT_EQ(wait_final(s, id)["status"], status);
    auto served = s.client().Get("/v1/jobs/" + id + "/net.json");
    ASSERT_EQ(served->status, 200);
    const std::string cmd = papernet::test::papernet_binary() + " unfold " +
                            (fs::path(papernet::test::test_data_dir()) / "mirror.ply").string() +
                            " " + flags + " -o " + out.string() + " -o " + pdf.string() +
                            " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const json cli = json::parse(read_file(out));
    EXPECT_EQ(without_seconds(cli), without_seconds(json::parse(served->body)));
    EXPECT_EQ(cli["mesh"]["faces"].size(), cli["net"]["faces"].size());
    EXPECT_EQ(cli.contains("print"), query.find("paper=none") == std::string::npos);
  }
  fs::remove(out);
  fs::remove(pdf);
}

// A bad option is the caller's fault, not the mesh's: 400 naming it, before any job exists;
// also one only the print checks (a sheet too small for its margins). A mesh in three parts
// gives three pieces; with strict=true it is the mesh's fault: the job fails with invalid_mesh
// and the validator's reasons.
TEST_P(ServeTest, BadPaperIs400NamingItAndAMeshInPartsIsPiecesOrStrictlyTheMeshProblem) {
  Server s({"--workers", "1"});
  auto c = s.client();
  const std::string cube = test_mesh("sample.obj");
  for (const char* query : {"?paper=B7", "?paper=12x12mm", "?paper=A4&margin_mm=60"}) {
    SCOPED_TRACE(query);
    auto res = c.Post(std::string("/v1/jobs") + query, cube, "model/obj");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
    const json problem = json::parse(res->body);
    EXPECT_TRUE(problem["option"] == "paper" || problem["option"] == "margin_mm") << res->body;
  }
  // A GLB sent as OBJ: its bytes say otherwise, 415 naming both.
  auto glb_as_obj = c.Post("/v1/jobs", test_mesh("Duck.glb"), "model/obj");
  expect_problem(glb_as_obj, 415, "unsupported_format");
  EXPECT_NE(glb_as_obj->body.find("glb by its content, not the declared obj"), std::string::npos)
      << glb_as_obj->body;
  auto multipart = c.Post(
      "/v1/jobs",
      httplib::MultipartFormDataItems{{"mesh", cube, "sample.obj", "model/obj"},
                                      {"options", R"({"paper":"A6"})", "", "application/json"}});
  ASSERT_TRUE(multipart);
  EXPECT_EQ(multipart->status, 400);
  EXPECT_EQ(json::parse(multipart->body)["option"], "paper");

  std::string parts;  // three tetrahedra apart
  for (int k = 0; k < 3; ++k) {
    const int x = 3 * k, b = 4 * k + 1;
    parts += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x + 1) + " 0 0\nv " +
             std::to_string(x) + " 1 0\nv " + std::to_string(x) + " 0 1\n";
    parts += "f " + std::to_string(b) + " " + std::to_string(b + 2) + " " + std::to_string(b + 1) +
             "\nf " + std::to_string(b) + " " + std::to_string(b + 1) + " " +
             std::to_string(b + 3) + "\nf " + std::to_string(b + 1) + " " + std::to_string(b + 2) +
             " " + std::to_string(b + 3) + "\nf " + std::to_string(b + 2) + " " +
             std::to_string(b) + " " + std::to_string(b + 3) + "\n";
  }
  const json failed = wait_final(s, submit(s, parts, "model/obj", "?strict=true"));
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"]["status"], 422);
  EXPECT_EQ(failed["error"]["code"], "invalid_mesh");
  EXPECT_EQ(failed["error"]["mesh"]["components"], 3);
  ASSERT_FALSE(failed["error"]["reasons"].empty()) << failed.dump();
  EXPECT_EQ(failed["error"]["reasons"][0]["code"], "several_components");
  // Without strict, every part is a piece; with components=largest, one, and it says so.
  const json pieces = wait_final(s, submit(s, parts, "model/obj"));
  ASSERT_EQ(pieces["status"], "succeeded") << pieces.dump();
  EXPECT_EQ(pieces["result"]["pieces"].size(), 3u);
  const json largest = wait_final(s, submit(s, parts, "model/obj", "?components=largest"));
  ASSERT_EQ(largest["status"], "succeeded") << largest.dump();
  EXPECT_EQ(largest["result"]["pieces"].size(), 1u);
  EXPECT_EQ(largest["result"]["repairs"][0]["code"], "dropped_components");
}

// The 202 shows the job as accepted: queued, phase queued, not started, whether or not a worker
// claimed it between the insert and the answer; polls then show documented phases only.
TEST_P(ServeTest, AcceptedJobIsQueuedWithADocumentedPhase) {
  Server s({"--workers", "2", "--reuse-results", "false"});
  // README "Progress": every phase a job reports.
  const std::set<std::string> phases = {
      "queued", "load",  "validate", "collapse",  "unfold", "uncollapse", "tabs",
      "layout", "write", "done",     "succeeded", "failed", "cancelled",  "approximated"};
  std::vector<std::string> ids;
  for (int i = 0; i < 6; ++i) {
    auto res = s.client().Post("/v1/jobs?strategy=TU", kNonManifoldObj, "model/obj");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 202) << res->body;
    const json job = body(res);
    EXPECT_EQ(job["status"], "queued") << job.dump();
    EXPECT_EQ(job["progress"]["phase"], "queued") << job.dump();
    EXPECT_TRUE(job["started"].is_null()) << job.dump();
    ids.push_back(job["id"]);
  }
  for (const std::string& id : ids) {
    for (;;) {
      const json job = body(s.client().Get("/v1/jobs/" + id));
      EXPECT_TRUE(phases.count(job["progress"]["phase"].get<std::string>())) << job.dump();
      if (job["status"] == "running") {
        EXPECT_FALSE(job["started"].is_null()) << job.dump();
      }
      if (job["status"] != "queued" && job["status"] != "running") break;
      std::this_thread::sleep_for(5ms);
    }
  }
}

// CORS: a page on a listed origin may call every route a browser uses (preflight included) and
// read the headers it needs; other origins get no CORS headers and a preflight 403.
TEST_P(ServeTest, CorsForConfiguredOriginsOnEveryBrowserRoute) {
  Server s({"--workers", "1", "--cors-origins", "https://shop.example, http://localhost:5173/"});
  auto c = s.client();
  const httplib::Headers shop = {{"Origin", "https://shop.example"}};
  const httplib::Headers evil = {{"Origin", "https://evil.example"}};

  auto preflight = c.Options("/v1/jobs", {{"Origin", "http://localhost:5173"},
                                          {"Access-Control-Request-Method", "POST"},
                                          {"Access-Control-Request-Headers",
                                           "authorization, content-type, idempotency-key"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->status, 204);
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Origin"), "http://localhost:5173");
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Methods"), "GET, HEAD, POST");
  const std::string allowed_headers = preflight->get_header_value("Access-Control-Allow-Headers");
  for (const char* h : {"Authorization", "Content-Type", "Idempotency-Key"})
    EXPECT_NE(allowed_headers.find(h), std::string::npos) << allowed_headers;
  auto job_preflight =
      c.Options("/v1/jobs/0123456789abcdef0123456789abcdef",
                {{"Origin", "https://shop.example"}, {"Access-Control-Request-Method", "DELETE"}});
  ASSERT_TRUE(job_preflight);
  EXPECT_EQ(job_preflight->status, 204);
  EXPECT_EQ(job_preflight->get_header_value("Access-Control-Allow-Methods"), "GET, HEAD, DELETE");
  auto refused = c.Options(
      "/v1/jobs", {{"Origin", "https://evil.example"}, {"Access-Control-Request-Method", "POST"}});
  expect_problem(refused, 403, "origin_not_allowed");
  EXPECT_FALSE(refused->has_header("Access-Control-Allow-Origin"));
  // An OPTIONS that is no preflight is still a method the path does not take.
  expect_problem(c.Options("/v1/jobs", shop), 405, "method_not_allowed");

  auto posted = c.Post("/v1/jobs?strategy=TU", shop, kNonManifoldObj, "model/obj");
  ASSERT_TRUE(posted);
  ASSERT_EQ(posted->status, 202) << posted->body;
  EXPECT_EQ(posted->get_header_value("Access-Control-Allow-Origin"), "https://shop.example");
  EXPECT_EQ(posted->get_header_value("Vary"), "Origin");
  const std::string exposed = posted->get_header_value("Access-Control-Expose-Headers");
  for (const char* h : {"Location", "Retry-After", "X-Papernet-Level", "Content-Disposition"})
    EXPECT_NE(exposed.find(h), std::string::npos) << exposed;
  const std::string id = body(posted)["id"];

  std::string stream;
  auto events = c.Get("/v1/jobs/" + id + "/events", shop, [&](const char* data, size_t n) {
    stream.append(data, n);
    return true;
  });
  ASSERT_TRUE(events);
  EXPECT_EQ(events->status, 200);
  EXPECT_EQ(events->get_header_value("Access-Control-Allow-Origin"), "https://shop.example");
  EXPECT_NE(stream.find("event: done"), std::string::npos) << stream;
  for (const std::string& path : std::vector<std::string>{
           "/v1/jobs/" + id, "/v1/jobs", "/v1/jobs/" + id + "/net.json",
           "/v1/jobs/" + id + "/net.svg", "/v1/jobs/" + id + "/net.pdf",
           "/v1/jobs/" + id + "/mesh.glb", "/v1/jobs/" + id + "/pages/1", "/v1/openapi.json"}) {
    SCOPED_TRACE(path);
    auto res = c.Get(path, shop);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    EXPECT_EQ(res->get_header_value("Access-Control-Allow-Origin"), "https://shop.example");
    auto other = c.Get(path, evil);
    ASSERT_TRUE(other);
    EXPECT_FALSE(other->has_header("Access-Control-Allow-Origin"));
  }
  // Errors carry the headers too, or the page could not read the problem.
  auto missing = c.Get("/v1/jobs/0123456789abcdef0123456789abcdef", shop);
  expect_problem(missing, 404, "job_not_found");
  EXPECT_EQ(missing->get_header_value("Access-Control-Allow-Origin"), "https://shop.example");
  auto no_texture = c.Get("/v1/jobs/" + id + "/textures/0", shop);  // the mesh has none
  ASSERT_TRUE(no_texture);
  EXPECT_EQ(no_texture->status, 404);
  EXPECT_EQ(no_texture->get_header_value("Access-Control-Allow-Origin"), "https://shop.example");
  // A sheet and a texture are fetched by the demo's page: preflight and methods as for results.
  for (const std::string path : {"/pages/2", "/textures/0"}) {
    SCOPED_TRACE(path);
    auto pre = c.Options("/v1/jobs/" + id + path, {{"Origin", "https://shop.example"},
                                                   {"Access-Control-Request-Method", "GET"}});
    ASSERT_TRUE(pre);
    EXPECT_EQ(pre->status, 204);
    EXPECT_EQ(pre->get_header_value("Access-Control-Allow-Methods"), "GET, HEAD");
    auto post = c.Post("/v1/jobs/" + id + path, shop, "x", "text/plain");
    expect_problem(post, 405, "method_not_allowed");
    EXPECT_EQ(post->get_header_value("Allow"), "GET, HEAD");
  }
  auto cancel = c.Delete("/v1/jobs/" + id, shop);
  expect_problem(cancel, 409, "job_finished");
  EXPECT_EQ(cancel->get_header_value("Access-Control-Allow-Origin"), "https://shop.example");
}

TEST_P(ServeTest, NoCorsUnlessConfiguredAndAnyOriginWithStar) {
  Server closed({"--workers", "1"});
  const httplib::Headers shop = {{"Origin", "https://shop.example"}};
  auto preflight = closed.client().Options(
      "/v1/jobs", {{"Origin", "https://shop.example"}, {"Access-Control-Request-Method", "POST"}});
  expect_problem(preflight, 405, "method_not_allowed");
  EXPECT_FALSE(preflight->has_header("Access-Control-Allow-Origin"));
  EXPECT_FALSE(closed.client().Get("/v1/jobs", shop)->has_header("Access-Control-Allow-Origin"));

  Server open({"--workers", "1", "--cors-origins", "*"});
  auto any = open.client().Get("/v1/jobs", shop);
  ASSERT_TRUE(any);
  EXPECT_EQ(any->get_header_value("Access-Control-Allow-Origin"), "*");
  EXPECT_FALSE(any->has_header("Vary"));
}

// Retention: a finished job past --retention loses its upload and files and answers 410
// job_expired; it leaves the list; a job that is not finished is kept.
// papernet_store_bytes from /metrics.
std::uint64_t store_bytes(const Server& s) {
  auto res = s.client().Get("/metrics");
  EXPECT_TRUE(res && res->status == 200);
  if (!res) return 0;
  const std::string name = "\npapernet_store_bytes ";
  const auto at = res->body.find(name);
  EXPECT_NE(at, std::string::npos) << res->body;
  return at == std::string::npos ? 0 : std::stoull(res->body.substr(at + name.size()));
}

TEST_P(ServeTest, FinishedJobsExpireAfterRetentionWith410) {
  Server s({"--workers", "1", "--retention", "1"});
  auto c = s.client();
  const std::string id = submit(s, kNonManifoldObj, "model/obj", "?strategy=TU");
  ASSERT_EQ(wait_final(s, id)["status"], "succeeded");
  const std::uint64_t held = store_bytes(s);  // its upload and results, unless already expired
  // Expiry comes within a sweep or two of the second passing: wait for it, then look.
  while (c.Get("/v1/jobs/" + id)->status == 200) std::this_thread::sleep_for(50ms);
  EXPECT_EQ(store_bytes(s), 0u) << "the expired job's upload and files are removed (held " << held
                                << " bytes)";
  expect_problem(c.Get("/v1/jobs/" + id), 410, "job_expired");
  for (const char* name : {"/net.json", "/net.svg", "/net.pdf", "/mesh.glb", "/events"})
    expect_problem(c.Get("/v1/jobs/" + id + name), 410, "job_expired");
  expect_problem(c.Delete("/v1/jobs/" + id), 410, "job_expired");
  EXPECT_EQ(body(c.Get("/v1/jobs"))["jobs"].size(), 0u);
  EXPECT_NE(s.log().find("retention: 1 finished jobs expired"), std::string::npos) << s.log();
  // The same mesh again is a new job that runs (nothing is reused from an expired one).
  const std::string again = submit(s, kNonManifoldObj, "model/obj", "?strategy=TU");
  const json job = body(c.Get("/v1/jobs/" + again));
  EXPECT_FALSE(job["result"].is_object() && job["result"]["metrics"].contains("reused_from"))
      << job.dump();
}

// --max-store: past it, the finished jobs that finished first expire early (410), until the
// store holds no more; the gauge papernet_store_bytes says what it holds.
TEST_P(ServeTest, PastMaxStoreTheJobsThatFinishedFirstExpireEarly) {
  std::uint64_t one = 0;  // one job's upload and results, measured without a bound
  {
    Server s({"--workers", "1", "--max-store", "0"});
    const std::string id = submit(s, kNonManifoldObj, "model/obj", "?strategy=TU&size_mm=100");
    ASSERT_EQ(wait_final(s, id)["status"], "succeeded");
    one = store_bytes(s);
  }
  ASSERT_GT(one, 1000u);
  // Room for two such jobs and a half: of four, the first two go.
  const std::uint64_t bound = one * 5 / 2;
  Server s({"--workers", "1", "--max-store", std::to_string(bound)});
  auto c = s.client();
  std::vector<std::string> ids;
  for (int size : {100, 110, 120, 130}) {  // four results, none reused from another
    ids.push_back(
        submit(s, kNonManifoldObj, "model/obj", "?strategy=TU&size_mm=" + std::to_string(size)));
    ASSERT_EQ(wait_final(s, ids.back())["status"], "succeeded");
  }
  // The sweep runs every 2 s with a bound: wait for the second job to go (at most 20 s).
  for (int i = 0; i < 200 && c.Get("/v1/jobs/" + ids[1])->status == 200; ++i)
    std::this_thread::sleep_for(100ms);
  expect_problem(c.Get("/v1/jobs/" + ids[0]), 410, "job_expired");
  expect_problem(c.Get("/v1/jobs/" + ids[1] + "/net.json"), 410, "job_expired");
  for (int k : {2, 3}) EXPECT_EQ(c.Get("/v1/jobs/" + ids[k] + "/net.json")->status, 200) << k;
  const std::uint64_t held = store_bytes(s);
  EXPECT_LE(held, bound);
  EXPECT_GT(held, one) << "the two newest jobs' files stay";
  EXPECT_NE(s.log().find("(--max-store)"), std::string::npos) << s.log();
}
