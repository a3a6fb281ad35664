// The fit layout's search (docs/print.md, "Fit layout"): of several ways to cut the net into
// pieces that fit a sheet, the print keeps the one that needs the fewest sheets for its pieces.
// Sheets are counted from the drawn pages.
#include <gtest/gtest.h>

#include <string>

#include "api/net_json.h"
#include "core/unfold/net_check.h"
#include "engine/internal/steps.h"
#include "engine/pipeline.h"
#include "tests/support/job_input.h"

namespace papernet::test {
namespace {

struct Printed {
  std::size_t pages = 0;
  int pieces = 0;
  NetDocument doc;
};

// `unfolded` printed on A4 with `seconds` for the search (0: only the largest pieces that fit).
Printed print(const UnfoldOutcome& unfolded, const JobOptions& options, double seconds) {
  UnfoldOutcome out = unfolded;
  Progress quiet;
  engine_detail::write_documents(options, {.svg_pages = true}, out, seconds, quiet);
  EXPECT_TRUE(out.print);
  return {out.documents.svg_pages.size(), out.print ? out.print->pieces : 0,
          read_net_json(out.documents.net_json)};
}

TEST(FitSearch, SmallerPiecesNestOntoFewerSheetsThanTheLargestThatFit) {
  JobOptions options;
  options.overview = false;  // every page a sheet to cut
  PipelineProgress quiet;
  // The net as unfolded, before any print cut it.
  const UnfoldOutcome unfolded = run_pipeline(data_file("sample.obj"), options, {}, {}, quiet);
  ASSERT_EQ(unfolded.net.pieces.size(), 1u);
  const Printed largest = print(unfolded, options, 0);
  const Printed searched = print(unfolded, options, 60);
  ASSERT_GT(largest.pages, 1u) << "sample.obj at 200 mm needs several sheets";
  EXPECT_LT(searched.pages, largest.pages);
  EXPECT_GT(searched.pieces, largest.pieces);
  // A sheet saved is worth at most 20 more pieces (kPiecesPerSheet).
  EXPECT_LE(searched.pieces - largest.pieces,
            20 * static_cast<int>(largest.pages - searched.pages));
  for (const Printed* p : {&largest, &searched}) {
    const NetCheckReport check = check_pieces(p->doc.mesh, p->doc.net, p->doc.piece);
    EXPECT_TRUE(check.ok()) << check.summary();
    ASSERT_TRUE(p->doc.print);
    EXPECT_EQ(static_cast<std::size_t>(p->doc.print->pages), p->pages);
  }
  std::printf("sample.obj on A4: %zu sheets with %d pieces; searched, %zu with %d\n", largest.pages,
              largest.pieces, searched.pages, searched.pieces);
}

}  // namespace
}  // namespace papernet::test
