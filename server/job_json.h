#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "server/service_records.h"

namespace papernet::server {

/// The names of result files a job can have, in the order the API lists them.
const std::vector<std::string>& result_file_names();

/// The result file of texture k of the net JSON's `textures` ("texture-k"), served at
/// /v1/jobs/{id}/textures/{k} and listed under the job's `links.textures`.
std::string texture_file_name(std::size_t index);

/// The result file of printed page `number` (1-based, as the page says "page k of n"):
/// "page-k.svg", served at /v1/jobs/{id}/pages/{k} and listed under the job's `links.pages`
/// (entry k - 1, the net JSON's `print.placements[i].page`).
std::string page_file_name(std::size_t number);

/// The Content-Disposition of result file `file` (a name of result_file_names(), page_file_name
/// or texture_file_name) of a job with `options` (options_to_json): inline, named after the
/// kit's title where the job has one ("Kitchen Duck.pdf", "Kitchen Duck - page 2.svg"), else
/// after the file ("net.pdf", "page-2.svg"); a texture's name ends as its `content_type`
/// (".png", ".jpg"). A name outside ASCII is sent as RFC 6266 asks: `filename` with "_" for
/// each such letter, and `filename*` in UTF-8.
std::string content_disposition(const nlohmann::json& options, const std::string& file,
                                const std::string& content_type);

/// A job as GET /v1/jobs/{id} shows it: status, progress, result summary, error, links.
/// `now` (seconds since the epoch) fills elapsed times.
nlohmann::json job_to_json(const JobView& view, double now);

/// ISO 8601 UTC with milliseconds ("2026-11-22T05:30:00.123Z"); null for 0.
nlohmann::json iso_time(double seconds_since_epoch);

}  // namespace papernet::server
