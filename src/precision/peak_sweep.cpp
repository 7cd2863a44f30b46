#include "stickslip/precision/peak_sweep.hpp"

#include <fmt/format.h>

#include <atomic>
#include <exception>
#include <optional>
#include <thread>

#include "stickslip/error.hpp"

namespace stickslip::precision {

const quantity_info& peak_statistic(const std::string& key, const std::string& name) {
  if (const auto* q = find_mean_statistic(name)) return *q;
  throw invalid_value(key, name, "a statistic with one value per realization: " +
                                     mean_statistic_names());
}

const char* to_string(peak_method m) noexcept {
  switch (m) {
    case peak_method::independent: return "independent";
    case peak_method::common: return "common";
    case peak_method::score: return "score";
  }
  return "?";
}

namespace {

// Why the score method does not apply to q (what a request for it throws),
// or nothing: the causal score is R's derivative over the Poisson switch
// rate.
std::optional<error> score_refusal(const sweep_peak_request& q) {
  if (q.over != "lambda")
    return invalid_value("over", q.over,
                         "lambda with the score method (the derivative is over the switch rate)");
  if (!q.statistic || std::string(q.statistic->summary_name) != "R")
    return invalid_value("statistic", q.statistic ? q.statistic->summary_name : "(none)",
                         "R with the score method");
  if (!has_poisson_switching(q.spec.base))
    return invalid_value("method", "score",
                         "common or independent for a belt given its rates or generator (the "
                         "score method needs Poisson switching at rate lambda)");
  return std::nullopt;
}

}  // namespace

bool score_applies(const sweep_peak_request& q) { return !score_refusal(q); }

peak_method peak_method_named(const std::string& key, const std::string& name,
                              const sweep_peak_request& q) {
  if (name == "auto") return score_applies(q) ? peak_method::score : peak_method::common;
  for (auto m : {peak_method::independent, peak_method::common, peak_method::score})
    if (name == to_string(m)) return m;
  throw invalid_value(key, name, "auto, common, score or independent");
}

namespace {

// The sweeps of one stage's groups. Without a runner of the caller's they
// run side by side on q.threads threads, one each (or their share when
// there are more threads than groups): a sweep gives the
// same bits on any number of threads, and a group's sweep is small (~1.4 ms
// of setup, and an idle tail on two threads: the score method's groups ran
// at 1.3 cores of 2). Errors are rethrown in group order, the first first.
std::vector<result_set> run_side_by_side(const std::vector<sweep_spec>& specs,
                                         const sweep_peak_request& q) {
  std::vector<result_set> out(specs.size());
  if (q.run) {
    for (std::size_t g = 0; g < specs.size(); ++g) out[g] = q.run(specs[g]);
    return out;
  }
  // More threads than groups: each group's sweep gets its share.
  const unsigned threads = q.threads ? q.threads : std::max(1u, std::thread::hardware_concurrency());
  const auto workers = static_cast<unsigned>(std::min<std::size_t>(specs.size(), threads));
  const unsigned each = std::max(1u, threads / std::max(1u, workers));
  std::vector<std::exception_ptr> failed(specs.size());
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t g; (g = next.fetch_add(1)) < specs.size();) {
      try {
        out[g] = run_sweep(specs[g], each);
      } catch (...) {
        failed[g] = std::current_exception();
      }
    }
  };
  {
    // jthread: joined on leaving the block, also when starting one throws.
    std::vector<std::jthread> pool;
    for (unsigned t = 1; t < workers; ++t) pool.emplace_back(work);
    work();
  }
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace

peak_result find_peak_by_sweeps(const sweep_peak_request& q) {
  if (!q.statistic) throw invalid_value("statistic", "(none)", "a per-realization statistic");
  validate(q.options);
  if (q.method == peak_method::score)
    if (auto refusal = score_refusal(q)) throw *refusal;
  // Both ends of the range must be valid models (and within the work bound).
  for (double x : {q.options.lo, q.options.hi}) {
    auto check = q.spec;
    check.axes.clear();
    set_parameter(check.base, q.over, x);
    validate(check);
  }
  const auto& moments = q.statistic->moments;
  const auto spec_at = [&](const std::vector<double>& xs, std::uint64_t n, std::uint64_t seed,
                           bool crn) {
    sweep_spec s = q.spec;
    s.axes = {axis{q.over, xs}};
    s.realizations = n;
    s.seed = seed;
    s.common_random_numbers = crn;
    s.target_statistic.clear();
    // The finder reads one mean per point; the family's statistics would
    // cost ~15 % (docs/performance.md) and are not among its statistics
    // unless asked for.
    if (q.statistic - quantities().data() < static_cast<std::ptrdiff_t>(paper_quantity_count))
      s.family_statistics = false;
    // Nor the pooled statistics, histograms and duration lists (about 15 %
    // less CPU; the means are the same bits).
    s.means_only = per_realization(q.statistic->sampled);
    // R's causal score only for the score method, the one that reads it
    // (keeps_causal_score; ~5 % of a means-only sweep).
    s.statistics.derivatives = q.method == peak_method::score;
    validate(s);
    return s;
  };
  const auto sweep_at = [&](const std::vector<double>& xs, std::uint64_t n, std::uint64_t seed,
                            bool crn) {
    const auto s = spec_at(xs, n, seed, crn);
    return q.run ? q.run(s) : run_sweep(s, q.threads);
  };
  // A stage's groups: one common-random-number sweep each, with seeds
  // hashed from (seed, stage, group).
  const auto run_groups = [&](const std::vector<double>& xs, std::uint64_t n, std::size_t groups,
                              std::uint64_t stage) {
    std::vector<sweep_spec> specs;
    for (std::size_t g = 0; g < groups; ++g)
      specs.push_back(spec_at(xs, n, stage_seed(stage_seed(q.spec.seed, stage), g), true));
    return run_side_by_side(specs, q);
  };
  if (q.method == peak_method::score) {
    // Each stage: `groups` sweeps with common random numbers across the
    // points (seeds as the common method's); each point's derivative is the
    // causal score with the finder's fixed baseline (exactly unbiased).
    score_peak_options so;
    so.base = q.options;
    const score_group_evaluator eval = [&](const std::vector<double>& xs, std::uint64_t n,
                                           std::size_t groups, std::uint64_t stage,
                                           double baseline) {
      std::vector<score_group> out(groups);
      const auto results = run_groups(xs, n, groups, stage);
      for (std::size_t g = 0; g < groups; ++g) {
        for (const auto& p : results[g].points) {
          out[g].value.push_back((p.stats.*moments).mean());
          out[g].derivative.push_back(
              p.stats.stick_fraction_causal_score.derivative_with_baseline(baseline));
        }
      }
      return out;
    };
    return find_peak_score(eval, so);
  }
  if (q.method == peak_method::common) {
    // Each stage: `groups` sweeps with common random numbers across the
    // points, seeds hashed from (seed, stage, group).
    common_peak_options co;
    co.base = q.options;
    const group_evaluator eval = [&](const std::vector<double>& xs, std::uint64_t n,
                                     std::size_t groups, std::uint64_t stage) {
      std::vector<std::vector<double>> means(groups);
      const auto results = run_groups(xs, n, groups, stage);
      for (std::size_t g = 0; g < groups; ++g)
        for (const auto& p : results[g].points) means[g].push_back((p.stats.*moments).mean());
      return means;
    };
    return find_peak_common(eval, co);
  }
  // One sweep per stage, every point its own streams.
  const evaluator eval = [&](const std::vector<double>& xs, std::uint64_t n, std::uint64_t stage) {
    const auto result = sweep_at(xs, n, stage_seed(q.spec.seed, stage), false);
    std::vector<evaluation> out;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const auto& m = result.points[i].stats.*moments;
      out.push_back({xs[i], m.mean(), m.std_error()});
    }
    return out;
  };
  return find_peak(eval, q.options);
}

}  // namespace stickslip::precision
