// Reference integrator: fixed-step RK4 with event location by bisection.
// See oracle.hpp for the method and its error. Deliberately written from the
// equation of motion only; it never uses the closed-form orbit.
#include "reference/oracle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace stickslip::reference {
namespace {

struct phase {
  double x, z;  // position x and velocity x'
};

// Finds, by bisection, the first point of (lo, hi] where `reached` holds,
// given !reached(lo) and reached(hi). Returns that point to the last bit.
template <class Pred>
double bisect(double lo, double hi, Pred reached) {
  while (true) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) return hi;
    (reached(mid) ? hi : lo) = mid;
  }
}

class reference_integrator {
 public:
  reference_integrator(const model_parameters& p, const initial_conditions& ic,
                       std::span<const double> switches, const oracle_options& o,
                       std::span<const double> samples)
      : k_over_m_(p.stiffness / p.mass),
        friction_acc_(p.friction_coefficient * p.gravity),
        stiffness_(p.stiffness),
        max_friction_(p.friction_coefficient * p.mass * p.gravity),
        window_(p.window),
        switches_(switches),
        samples_(samples),
        max_steps_(o.max_steps) {
    const double period = 2.0 * std::numbers::pi * std::sqrt(p.mass / p.stiffness);
    h_ = period / o.steps_per_period;
    stick_resolution_ = o.stick_resolution > 0 ? o.stick_resolution : 1e-6 * period;
    x_ = ic.position;
    z_ = ic.velocity;
    v_ = ic.belt_direction >= 0 ? p.belt_speed : -p.belt_speed;
    out_.step = h_;
    out_.stick_resolution = stick_resolution_;
  }

  oracle_result run() {
    current_ = episode{mode::slip, 0.0, 0.0, x_, v_, false};
    if (z_ == v_) {
      contact();
    } else {
      sigma_ = v_ > z_ ? 1.0 : -1.0;
    }
    while (t_ < window_) {
      take_samples();
      if (++iterations_ > max_steps_)
        throw std::runtime_error("reference oracle: step bound hit at t = " + std::to_string(t_));
      if (sticking_) {
        stick_step();
      } else {
        slip_step();
      }
    }
    finish();
    return std::move(out_);
  }

 private:
  // Slip: m x'' = -k x + mu m g sigma.
  [[nodiscard]] double acceleration(double x) const noexcept {
    return -k_over_m_ * x + friction_acc_ * sigma_;
  }
  // The stick condition |k x| <= mu m g.
  [[nodiscard]] bool inside_band(double x) const noexcept {
    return stiffness_ * std::abs(x) <= max_friction_;
  }

  // One classical RK4 step of the slip equation with sigma held fixed.
  [[nodiscard]] phase rk4(phase s, double tau) const noexcept {
    const double k1x = s.z, k1z = acceleration(s.x);
    const double k2x = s.z + 0.5 * tau * k1z, k2z = acceleration(s.x + 0.5 * tau * k1x);
    const double k3x = s.z + 0.5 * tau * k2z, k3z = acceleration(s.x + 0.5 * tau * k2x);
    const double k4x = s.z + tau * k3z, k4z = acceleration(s.x + tau * k3x);
    return {s.x + tau / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
            s.z + tau / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z)};
  }

  [[nodiscard]] bool switch_pending() const noexcept {
    return next_switch_ < switches_.size() && switches_[next_switch_] < window_;
  }
  // The next place a step must end: a belt switch, a sample time, t_a.
  [[nodiscard]] double next_stop() const noexcept {
    double stop = switch_pending() ? switches_[next_switch_] : window_;
    if (next_sample_ < samples_.size()) stop = std::min(stop, samples_[next_sample_]);
    return stop;
  }
  // Whether the step that reached t_ ended at the next belt switch (and not
  // only at a sample time).
  [[nodiscard]] bool switch_due() const noexcept {
    return switch_pending() && switches_[next_switch_] <= t_;
  }
  // The state at every sample time reached (after the events at t_ acted).
  void take_samples() {
    for (; next_sample_ < samples_.size() && samples_[next_sample_] <= t_; ++next_sample_)
      out_.samples.push_back(oracle_sample{samples_[next_sample_], x_, sticking_ ? v_ : z_, v_,
                                           v_ > 0 ? std::size_t{0} : std::size_t{1}, sticking_});
  }

  void record(event_kind kind) { out_.events.push_back(oracle_event{kind, t_, x_, v_}); }

  void emit(const episode& e) {
    if (e.end > e.start) out_.episodes.push_back(e);
  }

  // Relative velocity zero (x' = v) during a slip.
  void contact() {
    z_ = v_;  // exact up to the bisection resolution
    if (inside_band(x_)) {
      sticking_ = true;
      stick_start_ = t_;
      stick_position_ = x_;
      stick_velocity_ = v_;
      record(event_kind::stick_onset);
    } else {
      // |k x| > mu m g: x'' has the sign of -x whatever the friction, so
      // x' - v leaves zero with sign -sgn(x): sigma = sgn(v - x') = sgn(x).
      sigma_ = x_ > 0 ? 1.0 : -1.0;
      record(event_kind::slip_reversal);
    }
  }

  // A stick ends at t_ (band edge, belt switch, or end of window).
  void end_stick(bool censored) {
    sticking_ = false;
    const double duration = t_ - stick_start_;
    if (duration < stick_resolution_) {  // zero-time contact (grazing): not a stick
      out_.dropped_stick_durations.push_back(duration);
      return;
    }
    current_.end = stick_start_;
    emit(current_);
    out_.episodes.push_back(
        episode{mode::stick, stick_start_, t_, stick_position_, stick_velocity_, censored});
    current_ = episode{mode::slip, t_, 0.0, x_, v_, false};
  }

  void stick_step() {
    const double stop = next_stop();
    const bool reaches_stop = stop - t_ <= h_;
    const double tau = reaches_stop ? std::max(stop - t_, 0.0) : h_;
    // RK4 on x' = v is exact: x + v tau.
    auto beyond_band = [&](double dt) { return !inside_band(x_ + v_ * dt); };
    if (beyond_band(tau)) {
      const double dt = beyond_band(0.0) ? 0.0 : bisect(0.0, tau, beyond_band);
      x_ += v_ * dt;
      t_ = std::min(t_ + dt, stop);
      z_ = v_;
      // Beyond the edge the spring force exceeds mu m g and pulls the mass
      // back: x' - v takes the sign of -v, so sigma = sgn(v - x') = sgn(v).
      sigma_ = v_ > 0 ? 1.0 : -1.0;
      record(event_kind::stick_break);
      end_stick(false);
      return;
    }
    ++out_.rk4_steps;
    x_ += v_ * tau;
    t_ = reaches_stop ? stop : t_ + tau;
    if (!reaches_stop) return;
    if (t_ >= window_) {
      take_samples();  // t_a, still sticking
      end_stick(true);
      return;
    }
    if (!switch_due()) return;  // a sample time
    // Belt switch: the mass keeps x' = old v, the belt now runs at -v.
    z_ = v_;
    v_ = -v_;
    sigma_ = v_ > z_ ? 1.0 : -1.0;
    ++next_switch_;
    record(event_kind::belt_switch);
    end_stick(false);
  }

  void slip_step() {
    const double stop = next_stop();
    const bool reaches_stop = stop - t_ <= h_;
    const double tau = reaches_stop ? std::max(stop - t_, 0.0) : h_;
    const phase s0{x_, z_};
    const phase s1 = rk4(s0, tau);
    // g > 0 while slipping in direction sigma; g' = -sigma x''.
    auto g = [&](phase s) { return sigma_ * (v_ - s.z); };
    auto g_rate = [&](phase s) { return -sigma_ * acceleration(s.x); };
    auto contact_by = [&](double dt) { return g(rk4(s0, dt)) <= 0.0; };
    double dt_contact = -1.0;
    if (g(s0) > 0.0) {
      if (g(s1) <= 0.0) {
        dt_contact = bisect(0.0, tau, contact_by);
      } else if (g_rate(s0) < 0.0 && g_rate(s1) > 0.0) {
        // g has a minimum inside the step: a touch or a double crossing?
        const double dt_min =
            bisect(0.0, tau, [&](double dt) { return g_rate(rk4(s0, dt)) >= 0.0; });
        if (contact_by(dt_min)) dt_contact = bisect(0.0, dt_min, contact_by);
      }
    }
    if (dt_contact >= 0.0) {
      const phase s = rk4(s0, dt_contact);
      t_ = std::min(t_ + dt_contact, stop);
      x_ = s.x;
      z_ = s.z;
      contact();
      return;
    }
    ++out_.rk4_steps;
    x_ = s1.x;
    z_ = s1.z;
    t_ = reaches_stop ? stop : t_ + tau;
    if (!reaches_stop || t_ >= window_ || !switch_due()) return;
    v_ = -v_;  // belt switch during a slip: x, x' continuous
    ++next_switch_;
    record(event_kind::belt_switch);
    if (z_ == v_) {
      contact();
    } else {
      sigma_ = v_ > z_ ? 1.0 : -1.0;
    }
  }

  void finish() {
    take_samples();  // t_a
    if (sticking_) end_stick(true);
    current_.end = window_;
    current_.censored = true;
    if (out_.episodes.empty() || current_.end > current_.start) out_.episodes.push_back(current_);
    out_.episodes.back().censored = true;
  }

  // parameters
  double k_over_m_, friction_acc_, stiffness_, max_friction_, window_;
  std::span<const double> switches_;
  std::span<const double> samples_;
  std::size_t next_sample_ = 0;
  std::int64_t max_steps_;
  double h_ = 0, stick_resolution_ = 0;
  // state
  double t_ = 0, x_ = 0, z_ = 0, v_ = 0, sigma_ = 1;
  bool sticking_ = false;
  std::size_t next_switch_ = 0;
  std::int64_t iterations_ = 0;
  // the open stick and the open slip episode
  double stick_start_ = 0, stick_position_ = 0, stick_velocity_ = 0;
  episode current_{};
  oracle_result out_;
};

}  // namespace

oracle_result integrate_reference(const model_parameters& p, const initial_conditions& ic,
                                  std::span<const double> switch_times,
                                  const oracle_options& options,
                                  std::span<const double> sample_times) {
  return reference_integrator(p, ic, switch_times, options, sample_times).run();
}

}  // namespace stickslip::reference
