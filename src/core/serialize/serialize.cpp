// The messages of serialize.hpp: each a tag, then its pieces (serialize/codecs.hpp).
#include "stickslip/serialize.hpp"

#include <fmt/format.h>

#include "serialize/codecs.hpp"
#include "stickslip/error.hpp"

namespace stickslip {

using namespace serial;

namespace {

constexpr std::string_view spec_tag = "SSPC", unit_tag = "SSWU", result_tag = "SSBR",
                           prefix_tag = "SSMP";

// The fields as given (not resolved), in the order of scalar_parameters
// (the paper's seven, then the family's c, mu_s, mu_k; 0 = mu), and the belt's
// levels, rates and generator, each with its length (the layout id covers
// both name lists).
void put(writer& w, const model_parameters& p) {
  for (const auto& row : scalar_parameters) w.f64(p.*row.field);
  put_values(w, p.belt_levels);
  put_values(w, p.belt_rates);
  put_values(w, p.belt_generator);
}
model_parameters get_parameters(reader& r) {
  model_parameters p;
  for (const auto& row : scalar_parameters) p.*row.field = r.f64("model parameter");
  p.belt_levels = get_values(r, "belt levels");
  p.belt_rates = get_values(r, "belt rates");
  p.belt_generator = get_values(r, "belt generator");
  return p;
}

void put(writer& w, const work_unit& u) {
  w.u64(u.point);
  w.u64(u.block);
}
work_unit get_unit(reader& r) {
  work_unit u;
  u.point = static_cast<std::size_t>(r.u64("unit point"));
  u.block = r.u64("unit block");
  return u;
}

}  // namespace

// ---- sweep spec ----
bytes serialize(const sweep_spec& s) {
  writer w;
  w.header(spec_tag);
  put(w, s.base);
  w.f64(s.initial.position_min);
  w.f64(s.initial.position_max);
  w.f64(s.initial.velocity_min);
  w.f64(s.initial.velocity_max);
  w.i64(s.initial.belt_start);
  w.u64(s.axes.size());
  for (const auto& ax : s.axes) {
    w.str(ax.name);
    put_values(w, ax.values);
  }
  w.u64(s.realizations);
  w.u64(s.seed);
  w.u64(s.block_size);
  w.u64(s.histograms.bins);
  w.f64(s.histograms.stick_duration_max);
  w.f64(s.histograms.slip_duration_max);
  w.i64(s.max_events);
  w.u8(s.keep_records ? 1 : 0);
  w.u8(static_cast<std::uint8_t>(s.engine));
  w.u8(s.common_random_numbers ? 1 : 0);
  w.str(s.target_statistic);
  w.f64(s.target_halfwidth);
  w.u64(s.min_realizations);
  w.u8(s.family_statistics ? 1 : 0);
  w.u8(s.means_only ? 1 : 0);
  w.u64(s.uncertain.size());
  for (const auto& u : s.uncertain) {
    w.str(u.symbol);
    w.u8(static_cast<std::uint8_t>(u.law.family));
    put_values(w, u.law.arguments);
  }
  w.str(s.sensitivity_statistic);
  w.u8(to_bits(s.statistics));
  w.u64(s.statistics.rows.size());
  for (const auto& row : s.statistics.rows) w.str(row);
  w.u64(s.survival.bins);
  w.f64(s.survival.stick_duration_max);
  w.f64(s.survival.slip_duration_max);
  put_values(w, s.observe_times);
  // The burn-in only when there is one: a spec without it keeps the bytes
  // (and the journal identity) it had before the field.
  if (s.burn_in != 0.0) w.f64(s.burn_in);
  return w.take();
}

sweep_spec deserialize_sweep_spec(std::string_view in) {
  reader r(in);
  r.header(spec_tag);
  sweep_spec s;
  s.base = get_parameters(r);
  s.initial.position_min = r.f64("initial law");
  s.initial.position_max = r.f64("initial law");
  s.initial.velocity_min = r.f64("initial law");
  s.initial.velocity_max = r.f64("initial law");
  const auto belt = r.i64("initial belt direction");
  if (belt < -1 || belt > 1) throw corrupt(fmt::format("initial belt direction {}", belt));
  s.initial.belt_start = static_cast<int>(belt);
  s.axes.resize(r.count("grid axes", 16));
  for (auto& ax : s.axes) {
    ax.name = r.str("axis name");
    ax.values.resize(r.count("axis values", 8));
    for (double& v : ax.values) v = r.f64("axis value");
  }
  s.realizations = r.u64("realizations");
  s.seed = r.u64("seed");
  s.block_size = r.u64("block size");
  s.histograms.bins = static_cast<std::size_t>(r.u64("bins"));
  s.histograms.stick_duration_max = r.f64("stick_duration_max");
  s.histograms.slip_duration_max = r.f64("slip_duration_max");
  s.max_events = r.i64("max_events");
  s.keep_records = r.boolean("keep_records");
  const auto engine = r.u8("engine");
  if (engine > static_cast<std::uint8_t>(sweep_engine::reference))
    throw corrupt(fmt::format("unknown engine {}", engine));
  s.engine = static_cast<sweep_engine>(engine);
  s.common_random_numbers = r.boolean("common_random_numbers");
  s.target_statistic = r.str("target statistic");
  s.target_halfwidth = r.f64("target half-width");
  s.min_realizations = r.u64("min realizations");
  s.family_statistics = r.boolean("family_statistics");
  s.means_only = r.boolean("means_only");
  s.uncertain.resize(r.count("uncertain parameters", 17));
  for (auto& u : s.uncertain) {
    u.symbol = r.str("uncertain parameter");
    const auto family = r.u8("law family");
    if (family > static_cast<std::uint8_t>(law_family::beta))
      throw corrupt(fmt::format("unknown law family {}", family));
    u.law.family = static_cast<law_family>(family);
    u.law.arguments = get_values(r, "law arguments");
    // The canonical text parses back to the same law only when the
    // arguments are the family's and meet its constraints.
    bool valid = false;
    try {
      valid = parse_law(to_string(u.law), u.symbol) == u.law;
    } catch (const error&) {
    }
    if (!valid)
      throw corrupt(fmt::format("the law of {} is not a valid {} law", u.symbol,
                                to_string(u.law.family)));
  }
  s.sensitivity_statistic = r.str("sensitivity statistic");
  if (const auto bits = r.u8("statistics selection"); !from_bits(bits, s.statistics))
    throw corrupt(fmt::format("statistics selection {:#04x} names unknown groups", bits));
  s.statistics.rows.resize(r.count("statistics rows", 8));
  for (auto& row : s.statistics.rows) row = r.str("statistics row");
  if (!canonical_rows(s.statistics))
    throw corrupt(fmt::format("statistics selection '{}' is not canonical", to_string(s.statistics)));
  s.survival.bins = static_cast<std::size_t>(r.u64("survival bins"));
  s.survival.stick_duration_max = r.f64("survival stick_duration_max");
  s.survival.slip_duration_max = r.f64("survival slip_duration_max");
  s.observe_times = get_values(r, "observe times");
  if (r.remaining() > 0) {
    s.burn_in = r.f64("burn-in");
    if (!(s.burn_in > 0.0)) throw corrupt(fmt::format("burn-in {}", s.burn_in));
  }
  r.finish("sweep spec");
  return s;
}

// ---- work unit ----
bytes serialize(const work_unit& u) {
  writer w;
  w.header(unit_tag);
  put(w, u);
  return w.take();
}

work_unit deserialize_work_unit(std::string_view in) {
  reader r(in);
  r.header(unit_tag);
  auto u = get_unit(r);
  r.finish("work unit");
  return u;
}

// ---- block result ----
bytes serialize(const work_unit& u, const block_result& b) {
  writer w;
  w.header(result_tag);
  put(w, u);
  put(w, b.stats);
  w.u64(b.records.size());
  for (const auto& x : b.records) put(w, x);
  return w.take();
}

std::pair<work_unit, block_result> deserialize_unit_result(std::string_view in) {
  reader r(in);
  r.header(result_tag);
  std::pair<work_unit, block_result> out;
  out.first = get_unit(r);
  out.second.stats = get_statistics(r);
  out.second.records.resize(r.count("records", record_bytes()));
  for (auto& x : out.second.records) x = get_record(r);
  r.finish("block result");
  return out;
}

// ---- merged prefix ----
bytes serialize_merged_prefix(std::size_t point, std::uint64_t blocks,
                              const point_statistics& stats) {
  writer w;
  w.header(prefix_tag);
  w.u64(point);
  w.u64(blocks);
  put(w, stats);
  return w.take();
}

bytes serialize(const merged_prefix& p) { return serialize_merged_prefix(p.point, p.blocks, p.stats); }

merged_prefix deserialize_merged_prefix(std::string_view in) {
  reader r(in);
  r.header(prefix_tag);
  merged_prefix p;
  p.point = static_cast<std::size_t>(r.u64("prefix point"));
  p.blocks = r.u64("prefix blocks");
  p.stats = get_statistics(r);
  r.finish("merged prefix");
  return p;
}

bool is_merged_prefix(std::string_view in) noexcept { return in.starts_with(prefix_tag); }

}  // namespace stickslip
