// Reference integrator for the model family: fixed-step RK4 with event
// location by bisection. See model_oracle.hpp. Written from the equation of
// motion only; it never uses a closed form of the motion.
#include "reference/model_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace stickslip::reference {
namespace {

struct phase {
  double x, z;
};

template <class Pred>
double bisect(double lo, double hi, Pred reached) {
  while (true) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) return hi;
    (reached(mid) ? hi : lo) = mid;
  }
}

class model_reference {
 public:
  model_reference(const oscillator_model& md, const model_initial_state& ic,
                  std::span<const level_switch> switches, const oracle_options& o,
                  double tangency_band, std::span<const double> samples)
      : m_(md.mass), k_(md.stiffness), c_(md.damping),
        kinetic_force_(md.kinetic_friction * md.mass * md.gravity),
        static_force_(md.static_friction * md.mass * md.gravity),
        equal_friction_(md.static_friction == md.kinetic_friction),
        window_(md.window), levels_(md.belt.levels), switches_(switches), samples_(samples),
        max_steps_(o.max_steps) {
    const double w0 = std::sqrt(k_ / m_), gamma = c_ / (2.0 * m_);
    const double fastest = std::max(w0, gamma + std::sqrt(std::abs(gamma * gamma - w0 * w0)));
    h_ = 2.0 * std::numbers::pi / (o.steps_per_period * fastest);
    const double period = 2.0 * std::numbers::pi / w0;
    stick_resolution_ = o.stick_resolution > 0 ? o.stick_resolution : 1e-6 * period;
    double speed = 0;
    for (double v : levels_) speed = std::max(speed, std::abs(v));
    tangency_gap_ = tangency_band * std::max({speed, std::abs(ic.velocity), 1e-300});
    x_ = ic.position;
    z_ = ic.velocity;
    v_ = levels_[ic.level];
    level_ = ic.level;
    out_.step = h_;
    out_.stick_resolution = stick_resolution_;
    out_.initial_energy = energy();
  }

  model_oracle_result run() {
    current_ = episode{mode::slip, 0.0, 0.0, x_, v_, false};
    if (z_ == v_) {
      contact();
    } else {
      sigma_ = v_ > z_ ? 1.0 : -1.0;
    }
    while (t_ < window_) {
      take_samples();
      if (++iterations_ > max_steps_)
        throw std::runtime_error("model oracle: step bound hit at t = " + std::to_string(t_));
      if (sticking_) {
        stick_step();
      } else {
        slip_step();
      }
    }
    finish();
    out_.final_energy = energy();
    return std::move(out_);
  }

 private:
  // m x'' = -k x - c x' + sigma mu_k m g while slipping.
  [[nodiscard]] double acceleration(phase s) const noexcept {
    return (-k_ * s.x - c_ * s.z + sigma_ * kinetic_force_) / m_;
  }
  [[nodiscard]] double energy() const noexcept { return 0.5 * m_ * z_ * z_ + 0.5 * k_ * x_ * x_; }
  // A slip from s0 over tau (ending in s1): Simpson's rule for the
  // dissipation, the friction force is constant for the belt's work.
  void account_slip(phase s0, double tau, phase s1) {
    if (!(tau > 0.0)) return;
    const phase mid = rk4(s0, 0.5 * tau);
    auto simpson = [&](auto f) { return tau / 6.0 * (f(s0) + 4.0 * f(mid) + f(s1)); };
    out_.friction_dissipation += kinetic_force_ * simpson([&](phase s) { return std::abs(v_ - s.z); });
    out_.damping_dissipation += c_ * simpson([](phase s) { return s.z * s.z; });
    out_.belt_work += sigma_ * kinetic_force_ * v_ * tau;
  }
  // A stick from x0 over tau: f = k x + c v with x = x0 + v t.
  void account_stick(double x0, double tau) {
    out_.damping_dissipation += c_ * v_ * v_ * tau;
    out_.belt_work += v_ * (k_ * (x0 * tau + 0.5 * v_ * tau * tau) + c_ * v_ * tau);
  }
  // The force a stick needs at x on the belt v: k x + c v.
  [[nodiscard]] double stick_force(double x) const noexcept { return k_ * x + c_ * v_; }
  [[nodiscard]] bool inside_band(double x) const noexcept {
    return std::abs(stick_force(x)) <= static_force_;
  }

  [[nodiscard]] phase rk4(phase s, double tau) const noexcept {
    const phase k1{s.z, acceleration(s)};
    const phase p2{s.x + 0.5 * tau * k1.x, s.z + 0.5 * tau * k1.z};
    const phase k2{p2.z, acceleration(p2)};
    const phase p3{s.x + 0.5 * tau * k2.x, s.z + 0.5 * tau * k2.z};
    const phase k3{p3.z, acceleration(p3)};
    const phase p4{s.x + tau * k3.x, s.z + tau * k3.z};
    const phase k4{p4.z, acceleration(p4)};
    return {s.x + tau / 6.0 * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x),
            s.z + tau / 6.0 * (k1.z + 2.0 * k2.z + 2.0 * k3.z + k4.z)};
  }

  [[nodiscard]] bool switch_pending() const noexcept {
    return next_switch_ < switches_.size() && switches_[next_switch_].time < window_;
  }
  // The next place a step must end: a belt switch, a sample time, t_a.
  [[nodiscard]] double next_stop() const noexcept {
    double stop = switch_pending() ? switches_[next_switch_].time : window_;
    if (next_sample_ < samples_.size()) stop = std::min(stop, samples_[next_sample_]);
    return stop;
  }
  // Whether the step that reached t_ ended at the next belt switch (and not
  // only at a sample time).
  [[nodiscard]] bool switch_due() const noexcept {
    return switch_pending() && switches_[next_switch_].time <= t_;
  }
  // The state at every sample time reached (after the events at t_ acted).
  void take_samples() {
    for (; next_sample_ < samples_.size() && samples_[next_sample_] <= t_; ++next_sample_)
      out_.samples.push_back(
          oracle_sample{samples_[next_sample_], x_, sticking_ ? v_ : z_, v_, level_, sticking_});
  }
  void take_switch() {
    level_ = switches_[next_switch_].level;
    v_ = levels_[level_];
    ++next_switch_;
    grazing_ = false;
    record(event_kind::belt_switch);
  }

  void record(event_kind kind) { out_.events.push_back(oracle_event{kind, t_, x_, v_}); }
  void emit(const episode& e) {
    if (e.end > e.start) out_.episodes.push_back(e);
  }

  void contact() {
    z_ = v_;
    grazing_ = false;
    if (inside_band(x_)) {
      sticking_ = true;
      stick_start_ = t_;
      stick_position_ = x_;
      stick_velocity_ = v_;
      record(event_kind::stick_onset);
    } else {
      sigma_ = stick_force(x_) > 0 ? 1.0 : -1.0;
      record(event_kind::slip_reversal);
    }
  }

  void end_stick(bool censored) {
    sticking_ = false;
    const double duration = t_ - stick_start_;
    if (duration < stick_resolution_) {
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
    auto beyond_band = [&](double dt) { return !inside_band(x_ + v_ * dt); };
    if (v_ != 0.0 && beyond_band(tau)) {
      const double dt = beyond_band(0.0) ? 0.0 : bisect(0.0, tau, beyond_band);
      account_stick(x_, std::min(t_ + dt, stop) - t_);
      x_ += v_ * dt;
      t_ = std::min(t_ + dt, stop);
      z_ = v_;
      sigma_ = v_ > 0 ? 1.0 : -1.0;
      grazing_ = equal_friction_;
      record(event_kind::stick_break);
      end_stick(false);
      return;
    }
    ++out_.rk4_steps;
    account_stick(x_, (reaches_stop ? stop : t_ + tau) - t_);
    x_ += v_ * tau;
    t_ = reaches_stop ? stop : t_ + tau;
    if (!reaches_stop) return;
    if (t_ >= window_) {
      take_samples();  // t_a, still sticking
      end_stick(true);
      return;
    }
    if (!switch_due()) return;  // a sample time
    z_ = v_;  // the mass keeps the old belt velocity
    take_switch();
    sigma_ = v_ > z_ ? 1.0 : -1.0;
    end_stick(false);
  }

  void slip_step() {
    const double stop = next_stop();
    const bool reaches_stop = stop - t_ <= h_;
    const double tau = reaches_stop ? std::max(stop - t_, 0.0) : h_;
    const phase s0{x_, z_};
    const phase s1 = rk4(s0, tau);
    auto g = [&](phase s) { return sigma_ * (v_ - s.z); };
    auto g_rate = [&](phase s) { return -sigma_ * acceleration(s); };
    auto contact_by = [&](double dt) { return g(rk4(s0, dt)) <= 0.0; };
    double dt_contact = -1.0;
    if (g(s0) > 0.0) {
      if (g(s1) <= 0.0 && tau > 0.0) {
        dt_contact = bisect(0.0, tau, contact_by);
      } else if (g_rate(s0) < 0.0 && g_rate(s1) > 0.0) {
        const double dt_min =
            bisect(0.0, tau, [&](double dt) { return g_rate(rk4(s0, dt)) >= 0.0; });
        const double g_min = g(rk4(s0, dt_min));
        if (g_min <= 0.0) {
          dt_contact = bisect(0.0, dt_min, contact_by);
        }
        if (std::abs(g_min) < tangency_gap_ && !grazing_) {
          out_.near_tangencies.push_back(t_ + dt_min);
        }
      }
    } else if (g(s0) == 0.0 && g_rate(s0) > 0.0 && tau > 0.0 && g(s1) <= 0.0) {
      // A slip that leaves x' = v at a reversal just beyond the band edge
      // and comes back within this one step: the return lies after the
      // maximum of g. (A departure from the edge with mu_s > mu_k returns
      // after an arc of at least pi, never within one step.)
      const double dt_max = bisect(0.0, tau, [&](double dt) { return g_rate(rk4(s0, dt)) <= 0.0; });
      dt_contact = bisect(dt_max, tau, contact_by);
    }
    if (dt_contact >= 0.0) {
      const phase s = rk4(s0, dt_contact);
      account_slip(s0, dt_contact, s);
      // A contact where x' barely turns (|x''| tiny) is a near tangency too.
      if (!grazing_ && std::abs(acceleration(s)) * h_ < tangency_gap_)
        out_.near_tangencies.push_back(t_ + dt_contact);
      t_ = std::min(t_ + dt_contact, stop);
      x_ = s.x;
      z_ = s.z;
      contact();
      return;
    }
    ++out_.rk4_steps;
    account_slip(s0, tau, s1);
    x_ = s1.x;
    z_ = s1.z;
    t_ = reaches_stop ? stop : t_ + tau;
    if (!reaches_stop || t_ >= window_ || !switch_due()) return;
    take_switch();  // x, x' continuous
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

  double m_, k_, c_, kinetic_force_, static_force_;
  bool equal_friction_;
  double window_;
  std::vector<double> levels_;
  std::span<const level_switch> switches_;
  std::span<const double> samples_;
  std::size_t next_sample_ = 0, level_ = 0;
  std::int64_t max_steps_;
  double h_ = 0, stick_resolution_ = 0, tangency_gap_ = 0;
  double t_ = 0, x_ = 0, z_ = 0, v_ = 0, sigma_ = 1;
  bool sticking_ = false, grazing_ = false;
  std::size_t next_switch_ = 0;
  std::int64_t iterations_ = 0;
  double stick_start_ = 0, stick_position_ = 0, stick_velocity_ = 0;
  episode current_{};
  model_oracle_result out_;
};

}  // namespace

model_oracle_result integrate_model_reference(const oscillator_model& model,
                                              const model_initial_state& ic,
                                              std::span<const level_switch> switches,
                                              const oracle_options& options,
                                              double tangency_band,
                                              std::span<const double> sample_times) {
  return model_reference(model, ic, switches, options, tangency_band, sample_times).run();
}

}  // namespace stickslip::reference
