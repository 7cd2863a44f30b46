#include "reproduce_peaks.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "stickslip/error.hpp"
#include "stickslip/io/atomic_file.hpp"
#include "stickslip/serialize.hpp"

namespace stickslip::app {

namespace {

constexpr const char* kept_header = "stickslip peak search 1";

// Every field of a peak_result, in the order kept.
template <class F>
void for_each_field(precision::peak_result& p, F&& f) {
  f("argmax", p.argmax);
  f("argmax_lo", p.argmax_lo);
  f("argmax_hi", p.argmax_hi);
  f("sampling_halfwidth", p.sampling_halfwidth);
  f("model_bias", p.model_bias);
  f("max", p.max);
  f("max_lo", p.max_lo);
  f("max_hi", p.max_hi);
  f("window_lo", p.window_lo);
  f("window_hi", p.window_hi);
  f("realizations", p.realizations);
  f("stages", p.stages);
  f("points_in_fit", p.points_in_fit);
  f("target_met", p.target_met);
}

}  // namespace

std::string describe_request(const precision::sweep_peak_request& q) {
  const auto& o = q.options;
  return fmt::format(
      "spec {:016x} over {} statistic {} range {} {} log {} target {} scan {} window {} "
      "initial {} budget {} stages {} common {}{}",
      fingerprint(q.spec), q.over, q.statistic ? q.statistic->summary_name : "(none)", o.lo,
      o.hi, o.log_scan, o.target_halfwidth, o.scan_points, o.window_points,
      o.initial_realizations, o.max_total_realizations, o.max_stages,
      q.method == precision::peak_method::common,
      q.method == precision::peak_method::score ? " score" : "");
}

std::string kept_peak_text(const std::string& request, const precision::peak_result& p) {
  std::string t = fmt::format("{}\nrequest {}\n", kept_header, request);
  auto copy = p;
  for_each_field(copy, [&](const char* name, const auto& v) {
    t += fmt::format("{} {}\n", name, v);  // shortest text that reads back exactly
  });
  return t;
}

bool read_kept_peak(const std::string& text, const std::string& request,
                    precision::peak_result& p) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kept_header) return false;
  if (!std::getline(in, line) || line != "request " + request) return false;
  precision::peak_result r;
  bool ok = true;
  for_each_field(r, [&](const char* name, auto& v) {
    std::string key, value;
    if (!ok || !std::getline(in, line)) {
      ok = false;
      return;
    }
    std::istringstream cells(line);
    cells >> key >> value;
    if (key != name || value.empty()) {
      ok = false;
      return;
    }
    try {
      using T = std::decay_t<decltype(v)>;
      if constexpr (std::is_same_v<T, bool>)
        v = value == "true";
      else if constexpr (std::is_floating_point_v<T>)
        v = std::stod(value);
      else
        v = static_cast<T>(std::stoull(value));
    } catch (const std::exception&) {
      ok = false;
    }
  });
  if (ok) p = r;
  return ok;
}

study::peak_locator kept_peak_locator(std::string runs_dir, run::runner& r,
                                      const run::stop_token& stop,
                                      std::function<void(const std::string&)> log) {
  return [runs_dir, &r, &stop, log](const precision::sweep_peak_request& request,
                                    const std::string& id) {
    const std::string path = runs_dir + "/" + id + ".peak";
    const std::string key = describe_request(request);
    precision::peak_result p;
    if (std::ifstream in{path}) {
      std::stringstream text;
      text << in.rdbuf();
      if (read_kept_peak(text.str(), key, p)) {
        if (log) log(fmt::format("{}: the search kept in {} (not run again)", id, path));
        return p;
      }
      if (log) log(fmt::format("{}: {} is not this search's result; searching again", id, path));
    }
    auto q = request;
    q.run = [&r, &stop](const sweep_spec& s) {
      auto rs = run::run_unless_stopped(r, s, stop);
      if (!rs)
        throw error(interrupted_by(stop.reason()),
                    fmt::format("interrupted by {}: the finished sweeps and peak "
                                "searches are kept; continue with the same command and --resume",
                                run::signal_text(stop.reason())));
      return std::move(*rs);
    };
    p = precision::find_peak_by_sweeps(q);
    std::filesystem::create_directories(runs_dir);
    io::detail::write_text_atomically(
        path, [&](io::detail::text_sink& out) { out.write(kept_peak_text(key, p)); });
    return p;
  };
}

}  // namespace stickslip::app
