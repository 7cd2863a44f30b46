#include "parse_errors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>

#include "stickslip/error.hpp"
#include "stickslip/nearest_name.hpp"

namespace stickslip::app {
namespace {

void print_error(const std::string& message) {
  fmt::print(stderr, "stickslip: error: {}\n", message);
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

// Every spelling of every option of `cmd`: "--lambda", "--switch-rate", "-o", ...
std::vector<std::string> flag_names(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const auto* opt : cmd.get_options()) {
    for (const auto& l : opt->get_lnames()) names.push_back("--" + l);
    for (const auto& s : opt->get_snames()) names.push_back("-" + s);
  }
  return names;
}

// "--lambda=1" -> "--lambda"; values and negative numbers are not flags.
bool flag_token(const std::string& token, std::string& name) {
  if (token.size() < 2 || token[0] != '-') return false;
  if (token[1] != '-' && (std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.'))
    return false;
  if (token == "--") return false;
  name = token.substr(0, token.find('='));
  return true;
}

// The subcommand named in `args`, if any.
CLI::App* chosen_subcommand(CLI::App& app, const std::vector<std::string>& args) {
  for (const auto& a : args)
    for (auto* sub : app.get_subcommands([](CLI::App*) { return true; }))
      if (sub->get_name() == a) return sub;
  return nullptr;
}

}  // namespace

int report_parse_error(CLI::App& app, const CLI::ParseError& e,
                       const std::vector<std::string>& args) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  const int code = static_cast<int>(exit_code::invalid_input);
  CLI::App* sub = chosen_subcommand(app, args);
  const auto subs = subcommand_names(app);
  if (sub == nullptr) {
    std::string word;
    for (const auto& a : args)
      if (!a.empty() && a[0] != '-') {
        word = a;
        break;
      }
    if (word.empty())
      print_error(fmt::format("a subcommand is required: {} (stickslip --help)",
                              fmt::join(subs, ", ")));
    else
      print_error(fmt::format("unknown subcommand '{}'{} (subcommands: {})", word,
                              did_you_mean(nearest_name(word, subs)), fmt::join(subs, ", ")));
    return code;
  }
  const std::string where = fmt::format("`stickslip {}`", sub->get_name());
  const auto flags = flag_names(*sub);
  std::map<const CLI::Option*, std::vector<std::string>> seen;  // option -> spellings given
  for (const auto& a : args) {
    std::string name;
    if (!flag_token(a, name) || name == "-h" || name == "--help") continue;
    const auto* opt = sub->get_option_no_throw(name);
    if (opt == nullptr) {
      print_error(fmt::format("unknown flag '{}' for {}{} (stickslip {} --help lists them)",
                              name, where, did_you_mean(nearest_name(name, flags)), sub->get_name()));
      return code;
    }
    seen[opt].push_back(name);
  }
  for (const auto& [opt, given] : seen)
    if (given.size() > 1 && opt->get_expected_max() <= 1 && opt->get_type_size_max() > 0) {
      print_error(fmt::format("{} is given {} times; give each flag once", given.front(),
                              given.size()));
      return code;
    }
  // A flag that takes a value but is last, or followed by another flag.
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string name;
    if (!flag_token(args[i], name) || args[i].find('=') != std::string::npos) continue;
    const auto* opt = sub->get_option_no_throw(name);
    if (opt == nullptr || opt->get_type_size_max() == 0) continue;
    std::string next;
    if (i + 1 == args.size() || flag_token(args[i + 1], next)) {
      print_error(fmt::format("{} needs a value ({}) (stickslip {} --help)", name,
                              opt->get_type_name(), sub->get_name()));
      return code;
    }
  }
  print_error(fmt::format("{} (stickslip {} --help)", e.what(), sub->get_name()));
  return code;
}

}  // namespace stickslip::app
