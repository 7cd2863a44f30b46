// Uncertain model parameters (docs/uncertainty.md): a parameter given by a
// probability law instead of a value. Each realization draws its own value
// of every uncertain parameter from its own random substream
// (uncertain_draws.hpp), so a realization replays alone and results do not
// depend on threads, ranks, shards or resume.
//
// The laws and their arguments (named; uniform and loguniform also take two
// positional arguments, min then max):
//   uniform(min=A,max=B)                 A < B
//   loguniform(min=A,max=B)              0 < A < B: log X uniform
//   normal(mean=M,sd=S)                  S > 0; support the whole line
//   truncnormal(mean=M,sd=S,min=A,max=B) S > 0, A < B: normal(M, S) given A <= X <= B
//   lognormal(mean=M,cv=C)               M > 0, C > 0: the law's own mean and
//                                        coefficient of variation (not those of log X)
//   gamma(mean=M,cv=C)                   M > 0, C > 0: shape 1/C^2, scale M C^2
//                                        (the maximum-entropy law of a positive
//                                        quantity with known mean and mean log)
//   beta(mean=M,sd=S,min=A,max=B)        A < M < B, 0 < S^2 < (M-A)(B-M):
//                                        A + (B-A) Beta(a, b) with that mean and sd
// Every draw is the law's quantile of one open uniform u in (0, 1)
// (inverse transform), so a law is a pure function of u.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stickslip/parameters.hpp"

namespace stickslip {

enum class law_family : unsigned char {
  uniform,
  loguniform,
  normal,
  truncnormal,
  lognormal,
  gamma,
  beta
};

struct parameter_law {
  law_family family = law_family::uniform;
  // The named arguments in the family's canonical order: (min, max) for
  // uniform and loguniform; (mean, sd) normal; (mean, sd, min, max)
  // truncnormal; (mean, cv) lognormal and gamma; (mean, sd, min, max) beta.
  std::vector<double> arguments;
  friend bool operator==(const parameter_law&, const parameter_law&) = default;
};

// "uniform", "gamma", ...
[[nodiscard]] const char* to_string(law_family f) noexcept;
// The canonical text, e.g. "gamma(mean=5,cv=0.2)", with every argument
// named and written as the shortest decimal that reads back to the same
// double (fmt's "{}"), so that parse_law gives back the same bits. Used in outputs, TOML, the journal and error messages.
[[nodiscard]] std::string to_string(const parameter_law& law);

// Whether `text` is written as a law (an identifier then '('), as opposed
// to a number or a grid (lin:, log:, a list): how flags, TOML and Python
// tell a law from a value.
[[nodiscard]] bool looks_like_law(std::string_view text) noexcept;

// Parses a law. Throws invalid_input (exit 2) naming `parameter` (as the
// caller spells it for the user, e.g. "--mu"; messages start with it), the text
// and what is wrong: an unknown law (listing the known ones), a missing,
// unknown, repeated or non-finite argument, positional arguments where they
// are not allowed, or arguments outside the law's own constraints above.
[[nodiscard]] parameter_law parse_law(std::string_view text, std::string_view parameter);

// The law's quantile at u in (0, 1): the value a draw u gives.
[[nodiscard]] double quantile(const parameter_law& law, double u);
// The closure of the law's support [low, high] (infinite ends for normal,
// and +inf for lognormal and gamma).
[[nodiscard]] std::pair<double, double> support(const parameter_law& law);
// The law's mean and variance (exact, for tests and docs).
[[nodiscard]] double law_mean(const parameter_law& law);
[[nodiscard]] double law_variance(const parameter_law& law);

// A model parameter given by a law: `symbol` is a canonical parameter symbol
// (parameters.hpp: m k g mu V lambda ta c mu_s mu_k, v1..vN, r1 r2).
struct uncertain_parameter {
  std::string symbol;
  parameter_law law;
  friend bool operator==(const uncertain_parameter&, const uncertain_parameter&) = default;
};

// Throws invalid_input naming the parameter (as its flag, --mu-s), the law
// and the domain when a
// law's support can leave the parameter's domain (a normal for m, a
// negative rate, mu_k > mu_s possible given the other values and laws), when
// a symbol is unknown or given twice, or when it is also a grid axis
// (`axis_symbols`). `base` holds the values of the parameters that are not
// uncertain (a sweep calls it once per axis value, so a fixed mu_s on an
// axis is compared with a mu_k law at each of its values). Symbols must be
// canonical (canonical_symbol). A last check validates the model at every
// combination of the laws' extreme draws (the quantiles of the smallest and
// largest open uniform; each law alone beyond 10 laws).
void validate_laws(const model_parameters& base, std::span<const uncertain_parameter> laws,
                   std::span<const std::string> axis_symbols = {});

}  // namespace stickslip
