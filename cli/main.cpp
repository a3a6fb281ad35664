// The `papernet` program: one subcommand per job (info, unfold, serve).
#include <cstring>
#include <iostream>
#include <string_view>

#include "cli/commands.h"

namespace {

struct Command {
  std::string_view name;
  int (*run)(int, char**);
  std::string_view summary;
};

constexpr Command kCommands[] = {
    {"info", papernet::cli::info, "describe a mesh and every problem found in it"},
    {"serve", papernet::cli::serve, "run the HTTP job service (papernet serve --help)"},
    {"unfold", papernet::cli::unfold,
     "unfold a mesh into nets to print (papernet.net/2 JSON, SVG, PDF)"},
};

int usage(std::ostream& out, int code) {
  out << "usage: papernet <command> [options]\n\ncommands:\n";
  for (const Command& c : kCommands) out << "  " << c.name << "\t" << c.summary << "\n";
  out << "\n'papernet <command> --help' describes a command.\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage(std::cerr, 1);
  const std::string_view name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") return usage(std::cout, 0);
  for (const Command& c : kCommands)
    if (c.name == name) return c.run(argc - 1, argv + 1);
  std::cerr << "papernet: unknown command '" << name << "'\n";
  return usage(std::cerr, 1);
}
