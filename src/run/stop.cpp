#include "stickslip/run/stop.hpp"

#include <string.h>  // sigabbrev_np (glibc 2.32)

#include <fmt/format.h>

namespace stickslip::run {
namespace {
std::atomic<stop_token*> g_token{nullptr};
extern "C" void on_stop_signal(int sig) {
  if (auto* t = g_token.load()) t->request(sig);
}
}  // namespace

stop_on_signals::stop_on_signals(stop_token& token) {
  g_token.store(&token);
  for (std::size_t i = 0; i < std::size(stop_signals); ++i)
    old_[i] = std::signal(stop_signals[i], on_stop_signal);
}

stop_on_signals::~stop_on_signals() {
  for (std::size_t i = 0; i < std::size(stop_signals); ++i) std::signal(stop_signals[i], old_[i]);
  g_token.store(nullptr);
}

void ignore_stop_signals() noexcept {
  for (const int sig : stop_signals) std::signal(sig, SIG_IGN);
}

std::string signal_text(int signal) {
  const char* name = sigabbrev_np(signal);  // "INT"; null for an unknown number
  return name ? fmt::format("signal {} (SIG{})", signal, name) : fmt::format("signal {}", signal);
}

}  // namespace stickslip::run
