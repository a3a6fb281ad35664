// The fit search (docs/print.md, "Fit layout"): the print's first step with layout fit.
#include "engine/internal/fit_search.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <future>
#include <iterator>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/unfold/net_check.h"
#include "engine/internal/run_progress.h"
#include "print/arrange.h"
#include "print/grow.h"
#include "print/merge.h"
#include "print/nest.h"
#include "print/tendrils.h"

namespace papernet::engine_detail {
namespace {

// One way the fit search makes pieces (docs/print.md, "Fit layout").
struct FitWay {
  enum Kind { Cut, Grow, GrowForTabs, Regrow } kind;
  // Cut: the net cut into pieces that fit `shrink` x the room (smaller pieces nest into each
  // other's hollows and often fill fewer sheets), then glued back while two fit `glue` (at least
  // `shrink`) x the room together.
  double shrink = 1, glue = 0;
};

// The ways, tried in turn: the net's cuts at six sizes; pieces grown from single faces
// (grow_to_fit) as large as they grow, then only as large as leaves room for a tab on every cut
// inside a piece, then that with its small pieces grown again face by face (kRegrowFaces); then
// small cuts glued back up to 0.7 and 0.85 of the room (fewer pieces than the cuts at those
// sizes, shaped otherwise), and up to the whole room (fewer still, where they nest as well).
constexpr FitWay kFitWays[] = {
    {FitWay::Cut, 1},         {FitWay::Cut, 0.85},     {FitWay::Cut, 0.7},
    {FitWay::Cut, 0.6},       {FitWay::Cut, 0.5},      {FitWay::Cut, 0.4},
    {FitWay::Grow},           {FitWay::GrowForTabs},   {FitWay::Regrow},
    {FitWay::Cut, 0.5, 0.7},  {FitWay::Cut, 0.4, 0.7}, {FitWay::Cut, 0.6, 0.85},
    {FitWay::Cut, 0.4, 0.85}, {FitWay::Cut, 0.7, 1},   {FitWay::Cut, 0.5, 1},
    {FitWay::Cut, 0.4, 1}};

// With detail=auto, a label under the legible size costs as much as this many pieces: the detail
// was chosen for legible labels, and the few left under that size come from crowded short cut
// edges, which another way of making pieces may not have (a scan of 76,840 faces: 17 pieces with
// a label of 0.6 mm, or 19 with none, on the same sheets). With every face kept, or a number of
// faces asked for, small labels come from the detail, and the choice is sheets and pieces alone.
constexpr double kPiecesPerIllegibleLabel = 3;

// Where the fit search's tries leave the labels out, it keeps time for the chosen print's layout
// with its labels: this many times a try's average. One for the layout, one (at least) for moving
// labels where they print legibly; on a dense net that takes longer (rocker-arm at 16,000 faces:
// a try 0.6-1.0 s, the labelled layout 2.0-2.7 s), and the labels stop where the search's time
// ends (PrintOptions::label_seconds). Then at least this long for the labels, however late.
constexpr double kLabelledPaces = 2;
constexpr double kLeastLabelSeconds = 1e-3;

// Grown pieces of at most this many faces are grown again face by face in the search's ninth way
// (grow_to_fit's `regrow_faces`).
constexpr std::size_t kRegrowFaces = 6;

// A print's numbered pieces laid out and nested onto sheets, with its labels placed or not.
void lay_out_pages(const Mesh& mesh, FitPrint& print, const PrintOptions& options, double gap,
                   const PageOptions& page, Vec2 alone, LabelPass labels) {
  print.layout =
      layout_net(mesh, arrange_pieces(print.pieces.net, print.pieces.piece, gap), options,
                 print.pieces.piece, LargeFaces{print.pieces.large, alone}, labels);
  print.pages = nest_pages(print.layout, print.pieces.piece, page, kCutSpacingMm);
}

FitPrint lay_out_fit(const Mesh& mesh, FitPieces pieces, const PrintOptions& print, double gap,
                     const PageOptions& page, Vec2 alone, LabelPass labels) {
  // The pieces numbered in a build order, neighbours after each other (docs/print.md).
  FitPrint out{std::move(pieces), {}, {}, {}};
  out.graph = piece_graph(mesh, out.pieces.piece);
  std::vector<double> area(static_cast<std::size_t>(out.pieces.pieces), 0);
  for (std::size_t f = 0; f < out.pieces.piece.size(); ++f) {
    const auto& t = out.pieces.net.points[f];
    area[out.pieces.piece[f]] += 0.5 * std::abs(cross(t[1] - t[0], t[2] - t[0]));
  }
  renumber_pieces(out.pieces.piece, build_order(out.graph, area));
  out.graph = piece_graph(mesh, out.pieces.piece);
  lay_out_pages(mesh, out, print, gap, page, alone, labels);
  return out;
}

// The fit search (docs/print.md, "Fit layout"): the ways of kFitWays in turn, `threads` at a
// time, while `seconds` last (at least the first); the cheapest print is kept. The ways are
// started in order and the choice is made in order, so that it is the one a search of one way
// at a time makes: the cheapest of the ways tried, the first of those that cost the same, and
// none after the best so far prints on one sheet (no sheet left to save).
class FitSearch {
 public:
  FitSearch(const NetDocument& net, const Mesh& mesh, const FitSearchOptions& options)
      : net_(net),
        mesh_(mesh),
        print_(options.print),
        page_(options.page),
        tabs_(options.tabs),
        scale_(options.scale),
        gap_(options.gap),
        model_mm_(options.model_mm),
        label_price_(options.labels_count ? kPiecesPerIllegibleLabel : 0),
        room_(options.room),
        seconds_(options.seconds),
        may_tile_(options.may_tile),
        threads_(std::max(1, options.threads)),
        tendril_cuts_(options.tendril_cuts) {}

  // The cheapest print; none when a face is too large for the paper and the layout was not
  // asked for (tiled_because() says why).
  std::optional<FitPrint> run(Progress& progress) {
    std::vector<std::future<void>> helpers;
    for (int t = 1; t < threads_; ++t)
      helpers.push_back(std::async(std::launch::async, [this] { work(nullptr); }));
    work(&progress);
    for (auto& helper : helpers) helper.get();
    if (error_) std::rethrow_exception(error_);
    if (cancelled_) throw CancelledException();
    if (!tiled_because_.empty()) return std::nullopt;
    // The choice a search of one way at a time makes (the ways laid out are a prefix of the
    // list, less those it skips too).
    std::optional<std::size_t> best;
    std::size_t end = std::size(kFitWays);  // the ways that search lays out: those before
    for (std::size_t i = 0; i < std::size(kFitWays); ++i) {
      if (!tried_[i].cost) continue;
      if (!best || *tried_[i].cost < *tried_[*best].cost) best = i;
      if (tried_[*best].last) {
        end = i + 1;
        break;
      }
    }
    if (!best) throw std::logic_error("the fit search laid out no way");
    FitPrint chosen = std::move(kept_.at(*best));
    // Tendrils cut before the merge as well (docs/print.md, "Tendrils cut before the merge
    // too"): the merge's compacted pieces may keep no tendril whose cut saves the sheet that a cut
    // before it saves. Where that cut saves one, both are merged and the cheaper kept: cut first,
    // the sheet can cost more pieces than the merge alone leaves on as few.
    std::optional<FitPrint> cut_first = trimmed(chosen, progress);
    merge(chosen, progress);
    // Saving pieces, the way that costs least in sheets is merged as well, and kept when it ends
    // cheaper: its pieces, more but nested tighter, may merge into as few as the chosen way's on
    // fewer sheets (tests/data's thingi10k 134617: 6 pieces on 4 sheets so, where the way of the
    // fewest pieces laid out took 6 sheets for its 6 and merged no further).
    if (fewest_sheets_ && fewest_sheets_->way != *best && fewest_sheets_->way < end) {
      FitPrint other = std::move(fewest_sheets_->print);
      merge(other, progress);
      if (other.cost(label_price_, print_.prefer) < chosen.cost(label_price_, print_.prefer))
        chosen = std::move(other);
    }
    if (trim(chosen, progress)) merge(chosen, progress);
    if (cut_first) {
      merge(*cut_first, progress);
      if (trim(*cut_first, progress)) merge(*cut_first, progress);
      if (cut_first->cost(label_price_, print_.prefer) < chosen.cost(label_price_, print_.prefer))
        chosen = std::move(*cut_first);
    }
    // Its labels, where the tries (and the merge's) left them out: the same faces, tabs, strips
    // and sheets. They are moved where they print legibly while the search's time lasts after
    // the layout (as long as a try) that places them.
    if (tries_ == LabelPass::Unplaced) {
      PrintOptions labelled = print_;
      labelled.label_seconds = std::max(seconds_ - elapsed() - pace(), kLeastLabelSeconds);
      lay_out_pages(mesh_, chosen, labelled, gap_, page_, room_.alone, LabelPass::Placed);
    }
    return chosen;
  }

  const std::string& tiled_because() const { return tiled_because_; }

 private:
  struct OutOfTime {};

  // Seconds since the search started.
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  }

  // The seconds a layout took on average (none laid out yet: 0). Under the mutex while the
  // search's threads run.
  double pace() const {
    return laid_out_ == 0 ? 0 : laid_out_seconds_ / static_cast<double>(laid_out_);
  }

  // The seconds one more layout is expected to take, with the time kept for the chosen print's
  // labelled layout when the tries leave labels out: kLabelledPaces layouts.
  double one_more() const {
    return pace() * (1 + (tries_ == LabelPass::Unplaced ? kLabelledPaces : 0));
  }

  // The chosen way's pieces merged two at a time (print/merge.h, merge_pieces) where the print
  // costs less: as many sheets or fewer, fewer pieces to cut out and glue. While the search's
  // time lasts, at the pace of its layouts, within the job's merge budget. A merged piece need
  // only fit the sheet (room_.alone), not the room kept for tabs all round it: each merge is laid
  // out and nested with the tabs it gets before it is kept, and refused when its piece with them
  // fits no sheet.
  void merge(FitPrint& chosen, Progress& progress) {
    if (chosen.pieces.pieces <= 1 || laid_out_ == 0 || print_.merge_budget == 0) return;
    const double need = one_more();
    TabClearanceOptions tabs = tabs_;
    if (print_.tabs != TabMode::Auto) tabs.min_height = 0;
    double cost = chosen.cost(label_price_, print_.prefer);
    MergeBudget budget = MergeBudget::of_tests(print_.merge_budget);
    const double left = seconds_ - elapsed() - need;
    if (left <= 0) return;
    budget.seconds = std::isfinite(left) ? left : 0;
    const auto keep = [&](const FitPieces& merged) {
      if (progress.cancelled()) throw CancelledException();
      if (elapsed() + need > seconds_) throw OutOfTime{};
      if (!check_pieces(mesh_, merged.net, merged.piece).ok()) return false;
      FitPrint print;
      try {
        print = lay_out_fit(mesh_, merged, print_, gap_, page_, room_.alone, LabelPass::Unplaced);
      } catch (const InvalidOptionException& e) {
        if (e.code() != "face_too_large") throw;
        return false;  // the merged piece with its tabs fits no sheet
      }
      // Its labels only add to its cost (those under the legible size), and leave its sheets,
      // pieces and strips as they are: a merge that costs no less without them is refused before
      // they are placed, which is most of a layout's time on a net with small labels.
      if (!(print.cost(0, print_.prefer) < cost)) return false;
      if (tries_ == LabelPass::Placed) {
        if (elapsed() + need > seconds_) throw OutOfTime{};
        lay_out_pages(mesh_, print, print_, gap_, page_, room_.alone, LabelPass::Placed);
      }
      const double c = print.cost(label_price_, print_.prefer);
      if (!(c < cost)) return false;
      cost = c;
      chosen = std::move(print);
      return true;
    };
    // Phase "layout" from where the search left it to the end, as the merge spends its budget.
    class Reports : public Progress {
     public:
      Reports(Progress& job, double from) : job_(job), from_(from) {}
      void report(const ProgressInfo& info) override {
        engine_detail::report(job_, "layout", from_ + (1 - from_) * info.phase_fraction);
      }
      bool cancelled() override { return job_.cancelled(); }

     private:
      Progress& job_;
      double from_;
    } reports{progress, static_cast<double>(passed_) / std::size(kFitWays)};
    try {
      merge_pieces(mesh_, net_.piece, chosen.pieces, scale_, FitRoom{room_.alone, room_.alone},
                   tabs, budget, keep, &reports, threads_);
    } catch (const OutOfTime&) {
    }
  }

  // Tendrils cut off where that saves a sheet (docs/print.md, "Tendrils cut off to save a
  // sheet"): saving sheets, the chosen print's pieces cut tendril_cuts_ times where that most
  // shrinks their hulls (print/tendrils.h, cut_tendrils) and laid out, kept when they print on
  // fewer sheets at a lower cost; then each cut glued back, the last first, where the print costs
  // less without it. Within the search's time, at the pace of its layouts, until the job is
  // cancelled. Whether it was kept.
  bool trim(FitPrint& chosen, Progress& progress) {
    std::optional<FitPrint> cut = trimmed(chosen, progress);
    if (!cut) return false;
    chosen = std::move(*cut);
    return true;
  }

  // The print `trim` makes of `chosen`, where it keeps one.
  std::optional<FitPrint> trimmed(const FitPrint& chosen, Progress& progress) {
    const std::size_t sheets = chosen.pages.pages.size();
    if (print_.prefer != FitGoal::Sheets || sheets <= 1 || tendril_cuts_ <= 0) return std::nullopt;
    const auto lay_out = [&](const FitPieces& pieces) -> std::optional<FitPrint> {
      if (progress.cancelled()) throw CancelledException();
      if (elapsed() + one_more() > seconds_) return std::nullopt;
      try {
        return lay_out_fit(mesh_, pieces, print_, gap_, page_, room_.alone, LabelPass::Unplaced);
      } catch (const InvalidOptionException& e) {
        if (e.code() != "face_too_large") throw;
        return std::nullopt;  // a piece with its tabs fits no sheet
      }
    };
    // Labels only add to a print's cost (those under the legible size), as in the merge.
    const auto cost = [&](const FitPrint& print) { return print.cost(0, print_.prefer); };
    FitPieces pieces = chosen.pieces;
    const std::vector<TendrilCut> cuts = cut_tendrils(pieces, tendril_cuts_);
    if (cuts.empty()) return std::nullopt;
    std::optional<FitPrint> best = lay_out(pieces);
    if (!best || best->pages.pages.size() >= sheets || !(cost(*best) < cost(chosen)))
      return std::nullopt;
    for (auto it = cuts.rbegin(); it != cuts.rend(); ++it) {
      FitPieces fewer = best->pieces;
      undo_tendril_cut(fewer, *it);
      std::optional<FitPrint> print = lay_out(fewer);
      if (print && cost(*print) < cost(*best)) best = std::move(print);
    }
    if (tries_ == LabelPass::Placed) {
      if (elapsed() + one_more() > seconds_) return std::nullopt;
      lay_out_pages(mesh_, *best, print_, gap_, page_, room_.alone, LabelPass::Placed);
      if (!(best->cost(label_price_, print_.prefer) < chosen.cost(label_price_, print_.prefer)))
        return std::nullopt;
    }
    return best;
  }

  struct Tried {
    std::optional<double> cost;  // none: not laid out (yet)
    bool last = false;           // no way after it can cost less
  };

  // Whether no way after `print` can cost less (FitPrint::nothing_to_save).
  bool last(const FitPrint& print) const {
    return print.nothing_to_save(print_.prefer, static_cast<int>(net_.pieces.size()));
  }

  // Takes the next way, makes its pieces and lays them out, until the ways or the time run out.
  // Only the thread with `progress` reports and looks for cancellation.
  void work(Progress* progress) {
    try {
      for (;;) {
        std::size_t i;
        FitPieces cut;
        {
          std::lock_guard lock(mutex_);
          if (progress) {
            report(*progress, "layout", static_cast<double>(passed_) / std::size(kFitWays));
            if (progress->cancelled()) cancelled_ = true;
          }
          if (!next_pieces(i, cut)) return;
        }
        const auto started = std::chrono::steady_clock::now();
        // Where the tries place their labels, a way after one already laid out is laid out
        // without them first: its labels only add to its cost (those under the legible size)
        // and leave its sheets, pieces and strips as they are, so a way that a way before it
        // costs as little as it does without them cannot be the choice, and its labels, most of
        // a layout's time on a net with small labels, are not placed.
        const bool labels_last = tries_ == LabelPass::Placed && i > 0 && any_tried_before(i);
        FitPrint print = lay_out_fit(mesh_, std::move(cut), print_, gap_, page_, room_.alone,
                                     labels_last ? LabelPass::Unplaced : tries_);
        const bool beaten = labels_last && beaten_before(i, print.cost(0, print_.prefer)) &&
                            !fewest_sheets_yet(i, print.cost(0, FitGoal::Sheets));
        if (labels_last && !beaten)
          lay_out_pages(mesh_, print, print_, gap_, page_, room_.alone, LabelPass::Placed);
        const double took =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        std::lock_guard lock(mutex_);
        laid_out_seconds_ += took;
        ++laid_out_;
        ++passed_;
        if (beaten)
          tried_[i] = {print.cost(0, print_.prefer), last(print)};  // at most its cost: not kept
        else
          keep(i, std::move(print));
      }
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }

  // The next way's pieces, under the lock: false when the search is over (the time, a print on
  // one sheet, an error, a cancellation, or a face too large for the paper). Ways that give the
  // pieces of the way before (skipped by a search of one way at a time) are passed over here.
  bool next_pieces(std::size_t& i, FitPieces& cut) {
    for (;;) {
      if (next_ >= std::size(kFitWays) || error_ || cancelled_ || !tiled_because_.empty())
        return false;
      if (next_ > 0) {
        // Another way only while one more as long as the average ends in the time left (with
        // the time kept for the labels), and while the best so far leaves sheets (or pieces)
        // to save.
        if (laid_out_ > 0 && elapsed() + one_more() > seconds_) return false;
        if (!kept_.empty() && last(kept_.rbegin()->second)) return false;
      }
      i = next_++;
      const FitWay way = kFitWays[i];
      // Without tabs, the growths for tabs are the growth before.
      if (way.kind != FitWay::Cut && way.kind != FitWay::Grow && print_.tabs != TabMode::Auto) {
        ++passed_;
        continue;
      }
      try {
        cut = way.kind == FitWay::Cut
                  ? cut_to_fit(net_.net, net_.piece, scale_, room_, page_.paper.name, model_mm_,
                               way.shrink, way.glue)
                  : grow_to_fit(mesh_, net_.piece, scale_, room_,
                                way.kind == FitWay::Grow ? 0 : tabs_.min_height, tabs_.angle_deg,
                                way.kind == FitWay::Regrow ? kRegrowFaces : 0);
      } catch (const InvalidOptionException& e) {
        // Asked for, fit is what the user gets or an error; by default, a kit taped from tiles.
        if (!may_tile_ || e.code() != "face_too_large") throw;
        tiled_because_ = e.what();
        return false;
      }
      // The same pieces as the cut before, or the growth before (regrown: no fewer pieces, the
      // growth kept as it was).
      bool same = false;
      if (way.kind == FitWay::Cut) {
        same = cut.pieces == last_cut_;
        last_cut_ = cut.pieces;
      } else {
        // A new net, unlike the cuts of a checked one: printed only when it passes the check.
        same = (way.kind == FitWay::Regrow && cut.pieces == last_grown_) ||
               !check_pieces(mesh_, cut.net, cut.piece).ok();
        if (!same) last_grown_ = cut.pieces;
      }
      if (!same) return true;
      ++passed_;
    }
  }

  // Whether a way before way i has been laid out (under the lock).
  bool any_tried_before(std::size_t i) {
    std::lock_guard lock(mutex_);
    return std::any_of(tried_.begin(), tried_.begin() + static_cast<std::ptrdiff_t>(i),
                       [](const Tried& t) { return t.cost.has_value(); });
  }

  // Whether a way before way i costs at most `cost` (under the lock): then way i, costing that
  // much or more, is not the choice. A way passed over so keeps its cost without labels, at most
  // its cost, which the way that beat it beats as well.
  bool beaten_before(std::size_t i, double cost) {
    std::lock_guard lock(mutex_);
    return std::any_of(tried_.begin(), tried_.begin() + static_cast<std::ptrdiff_t>(i),
                       [&](const Tried& t) { return t.cost && *t.cost <= cost; });
  }

  // Saving pieces, whether way i, costing `sheets` in sheets without its labels (they only add to
  // it), may cost the least in sheets of the ways laid out so far (under the lock): then it is
  // laid out with its labels and kept aside (keep) however many pieces it has.
  bool fewest_sheets_yet(std::size_t i, double sheets) {
    if (print_.prefer != FitGoal::Pieces) return false;
    std::lock_guard lock(mutex_);
    return fewer_sheets_than_aside(i, sheets);
  }

  // Whether way i, costing `sheets` in sheets, goes before the way kept aside for costing the
  // least in sheets (none yet, less, or as much and earlier). Under the lock.
  bool fewer_sheets_than_aside(std::size_t i, double sheets) const {
    return !fewest_sheets_ || sheets < fewest_sheets_->cost ||
           (sheets == fewest_sheets_->cost && i < fewest_sheets_->way);
  }

  // Keeps way i's print, under the lock, while it can still be the choice: while no way before
  // it costs as little. Those after it that cost as much or more go, so that of the prints kept
  // each costs less than those before it. Saving pieces, it is also kept aside while it costs
  // the least in sheets (the first of those that cost the same).
  void keep(std::size_t i, FitPrint print) {
    if (print_.prefer == FitGoal::Pieces) {
      const double sheets = print.cost(label_price_, FitGoal::Sheets);
      if (fewer_sheets_than_aside(i, sheets)) fewest_sheets_ = {i, sheets, print};
    }
    const double cost = print.cost(label_price_, print_.prefer);
    tried_[i] = {cost, last(print)};
    for (std::size_t j = 0; j < i; ++j)
      if (tried_[j].cost && *tried_[j].cost <= cost) return;
    for (auto it = kept_.upper_bound(i); it != kept_.end();)
      it = *tried_[it->first].cost >= cost ? kept_.erase(it) : std::next(it);
    kept_.emplace(i, std::move(print));
  }

  const NetDocument& net_;
  const Mesh& mesh_;
  const PrintOptions& print_;
  const PageOptions& page_;
  const TabClearanceOptions tabs_;
  const double scale_, gap_, model_mm_, label_price_;
  // How the tries lay out their labels: only where labels under the legible size count in a
  // print's cost are they placed; elsewhere the tries' sheets, pieces and strips are those of the
  // same layout with its labels (print/layout.h, LabelPass), and only the chosen print places
  // them, once.
  const LabelPass tries_ = label_price_ > 0 ? LabelPass::Placed : LabelPass::Unplaced;
  const FitRoom room_;
  const double seconds_;
  const bool may_tile_;
  const int threads_;
  const int tendril_cuts_;
  const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();

  std::mutex mutex_;  // guards what follows
  std::size_t next_ = 0, passed_ = 0;
  int last_cut_ = -1, last_grown_ = -1;
  double laid_out_seconds_ = 0;
  std::size_t laid_out_ = 0;
  std::array<Tried, std::size(kFitWays)> tried_{};
  // Each print kept costs less than those kept before it: the best so far is the last.
  std::map<std::size_t, FitPrint> kept_;
  // Saving pieces (FitGoal::Pieces), the way laid out with its labels that costs least in
  // sheets, merged too (run).
  struct Kept {
    std::size_t way;
    double cost;
    FitPrint print;
  };
  std::optional<Kept> fewest_sheets_;
  std::exception_ptr error_;
  bool cancelled_ = false;
  std::string tiled_because_;
};

}  // namespace

double FitPrint::cost(double label_price, FitGoal goal) const {
  const auto cut_out = static_cast<double>(pieces.pieces) + layout.strips.size() +
                       label_price * static_cast<double>(label_sizes(layout).illegible);
  const auto sheets = static_cast<double>(pages.pages.size());
  return goal == FitGoal::Sheets ? sheets + cut_out / kPiecesPerSheet
                                 : cut_out + sheets / kPiecesPerSheet;
}

bool FitPrint::nothing_to_save(FitGoal goal, int parts) const {
  return pages.pages.size() <= 1 &&
         (goal == FitGoal::Sheets || (pieces.pieces <= parts && layout.strips.empty()));
}

FitChoice search_fit(const NetDocument& net, const Mesh& mesh, const FitSearchOptions& options,
                     Progress& progress) {
  FitSearch search{net, mesh, options};
  FitChoice choice;
  choice.print = search.run(progress);
  if (!choice.print) choice.tiled_because = search.tiled_because();
  return choice;
}

}  // namespace papernet::engine_detail
