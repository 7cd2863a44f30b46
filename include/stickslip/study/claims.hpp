// The paper's quantitative claims, each evaluated for one or more parameter
// sets of the study (claims.cpp writes every verdict rule next to its claim).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "stickslip/study/paper_study.hpp"

namespace stickslip::study {

enum class verdict { agrees, partly, disagrees, not_evaluated };
[[nodiscard]] const char* to_string(verdict v) noexcept;

// One quantitative claim of the paper, evaluated for one parameter set.
struct claim_value {
  std::string value;  // our number(s), formatted
  std::string ci95;   // our 95 % interval, formatted (may be empty)
  verdict result = verdict::not_evaluated;
  std::string note;   // how the verdict was reached
};

struct claim {
  std::string id;           // short key: "dmax", "Rmax_mu5", ...
  std::string statement;    // what the paper says
  std::string paper_value;  // as printed
  std::vector<claim_value> per_set;  // in the order of the sets evaluated
};

// Evaluates every claim for each set study (in order).
[[nodiscard]] std::vector<claim> evaluate_claims(const std::vector<const set_study*>& sets);

// Number of claims with verdict `agrees` (partly counts one half).
[[nodiscard]] double claim_score(const std::vector<claim>& claims, std::size_t set_index);

}  // namespace stickslip::study
