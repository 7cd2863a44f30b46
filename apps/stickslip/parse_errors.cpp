#include "parse_errors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>

#include "stickslip/error.hpp"

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

std::string did_you_mean(const std::string& guess) {
  return guess.empty() ? "" : fmt::format("; did you mean {}?", guess);
}

}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // Optimal string alignment distance, O(|a| |b|).
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates)
    if (const auto dist = edit_distance(word, c); dist < best_distance) {
      best = c;
      best_distance = dist;
    }
  return best;
}

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
                              did_you_mean(nearest(word, subs)), fmt::join(subs, ", ")));
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
                              name, where, did_you_mean(nearest(name, flags)), sub->get_name()));
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
