#pragma once

namespace papernet::cli {

/// Each subcommand of the `papernet` binary; argv[0] is the subcommand's name.
/// Returns the process exit code.
int info(int argc, char** argv);
int serve(int argc, char** argv);
int unfold(int argc, char** argv);

}  // namespace papernet::cli
