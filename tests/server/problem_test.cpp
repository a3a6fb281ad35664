#include "server/problem.h"

#include <gtest/gtest.h>

#include "api/options.h"
#include "core/errors.h"

using namespace papernet;
using namespace papernet::server;

namespace {

template <class E>
Problem mapped(E error) {
  try {
    throw error;
  } catch (...) {
    return problem_from_exception(std::current_exception());
  }
}

}  // namespace

TEST(ProblemTest, EveryFailureMapsToItsStatusAndCode) {
  EXPECT_EQ(mapped(InvalidOptionException("unknown_option", "x", "unknown option 'x'")).status,
            400);
  EXPECT_EQ(mapped(ApiError("job_not_found", "no job")).status, 404);
  EXPECT_EQ(mapped(ApiError("payload_too_large", "big")).status, 413);
  EXPECT_EQ(mapped(ApiError("unsupported_format", "png")).status, 415);
  EXPECT_EQ(mapped(InvalidInputException("edge 3-4 is non-manifold")).status, 422);
  EXPECT_EQ(mapped(InvalidInputException("x")).code, "invalid_mesh");
  EXPECT_EQ(mapped(IOException("truncated")).code, "unreadable_mesh");
  using Limit = LimitExceededException::Limit;
  EXPECT_EQ(mapped(LimitExceededException(Limit::Faces, "1e9 faces")).code, "too_many_faces");
  EXPECT_EQ(mapped(LimitExceededException(Limit::Vertices, "1e9 points")).status, 413);
  EXPECT_EQ(mapped(LimitExceededException(Limit::Bytes, "1 TB")).code, "payload_too_large");
  EXPECT_EQ(mapped(LimitExceededException(Limit::Pixels, "1e9 pixels")).code, "image_too_large");
  EXPECT_EQ(mapped(LimitExceededException(Limit::Pixels, "1e9 pixels")).status, 413);
  EXPECT_EQ(mapped(ApiError("queue_full", "full")).status, 429);
  EXPECT_EQ(mapped(ApiError("shutting_down", "bye")).status, 503);
  EXPECT_EQ(mapped(std::runtime_error("boom")).status, 500);
  EXPECT_EQ(mapped(CancelledException()).code, "job_cancelled");
}

TEST(ProblemTest, OptionErrorsNameTheOption) {
  const Problem p = mapped(InvalidOptionException("option_out_of_range", "seed", "too big"));
  EXPECT_EQ(p.code, "option_out_of_range");
  EXPECT_EQ(p.extra["option"], "seed");
  EXPECT_EQ(p.detail, "too big");
  // The print's refusals while the job runs: 422, the option named (engine/detail.cpp).
  for (const char* code : {"face_too_large", "print_too_large"}) {
    const Problem print = mapped(InvalidOptionException(code, "size_mm", "at most 2,792 mm"));
    EXPECT_EQ(print.status, 422) << code;
    EXPECT_EQ(print.code, code);
    EXPECT_EQ(print.extra["option"], "size_mm");
  }
}

TEST(ProblemTest, RetryAfterOnQueueFullAndShutdown) {
  EXPECT_TRUE(make_problem("queue_full", "").retry_after);
  EXPECT_TRUE(make_problem("shutting_down", "").retry_after);
  EXPECT_FALSE(make_problem("job_not_found", "").retry_after);
}

TEST(ProblemTest, UnknownCodeIsAnInternalError) {
  const Problem p = make_problem("no_such_code", "x");
  EXPECT_EQ(p.status, 500);
  EXPECT_EQ(p.code, "internal_error");
}

TEST(ProblemTest, JsonIsRfc9457AndRoundTrips) {
  const Problem p = make_problem("invalid_mesh", "3 non-manifold edges", {{"reasons", {"a", "b"}}});
  const nlohmann::json doc = problem_json(p, "/v1/jobs/x");
  EXPECT_EQ(doc["status"], 422);
  EXPECT_EQ(doc["code"], "invalid_mesh");
  EXPECT_EQ(doc["instance"], "/v1/jobs/x");
  EXPECT_TRUE(doc["type"].get<std::string>().find("invalid_mesh") != std::string::npos);
  EXPECT_FALSE(doc["title"].get<std::string>().empty());
  const Problem back = problem_from_json(doc);
  EXPECT_EQ(back.status, 422);
  EXPECT_EQ(back.code, "invalid_mesh");
  EXPECT_EQ(back.extra["reasons"].size(), 2u);
}
