#include "stickslip/mpi/distributed_sweep.hpp"

#include <mpi.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <fmt/format.h>
#include <mutex>
#include <numbers>
#include <optional>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/serialize.hpp"

namespace stickslip::mpi {
namespace {

enum tag : int { request_tag = 1, work_tag = 2, result_tag = 3, failure_tag = 4 };
constexpr auto poll_pause = std::chrono::microseconds(200);

unsigned resolve_threads(unsigned threads) {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw error(exit_code::internal, fmt::format("MPI: {} failed ({})", what, rc));
}

int checked_size(std::size_t n) {
  if (n > static_cast<std::size_t>(INT_MAX))
    throw error(exit_code::internal, fmt::format("MPI message of {} bytes is too large", n));
  return static_cast<int>(n);
}

void send_bytes(const std::string& data, int dest, int t) {
  check(MPI_Send(data.data(), checked_size(data.size()), MPI_BYTE, dest, t, MPI_COMM_WORLD),
        "MPI_Send");
}

// Receives the message that MPI_Probe/Iprobe reported in `st`.
std::string receive_bytes(const MPI_Status& st) {
  int n = 0;
  check(MPI_Get_count(&st, MPI_BYTE, &n), "MPI_Get_count");
  std::string data(static_cast<std::size_t>(n), '\0');
  check(MPI_Recv(data.data(), n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE),
        "MPI_Recv");
  return data;
}

std::string encode_indices(const std::vector<std::uint64_t>& v) {
  detail::byte_writer w;
  for (auto i : v) w.u64(i);
  return w.take();
}
std::vector<std::uint64_t> decode_indices(const std::string& data) {
  if (data.size() % 8) throw detail::corrupt("work list length is not a multiple of 8");
  detail::byte_reader r(data);
  std::vector<std::uint64_t> v(data.size() / 8);
  for (auto& i : v) i = r.u64("unit index");
  return v;
}

// The units hooks.wanted selects, costliest points first (points_by_cost, as
// run_units does), blocks in order within a point, so cheap units fill the tail.
std::vector<std::uint64_t> units_to_run(const sweep_spec& s, const sweep_hooks& hooks) {
  const auto nb = blocks_per_point(s);
  std::vector<std::uint64_t> out;
  for (auto point : points_by_cost(s))
    for (std::uint64_t b = 0; b < nb; ++b)
      if (!hooks.wanted || hooks.wanted(work_unit{point, b})) out.push_back(point * nb + b);
  return out;
}

// First error wins; stored as code + message so it can cross ranks.
struct failure_slot {
  std::optional<error> first;
  void set(const std::exception_ptr& e) {
    if (first) return;
    try {
      std::rethrow_exception(e);
    } catch (const error& x) {
      first = x;
    } catch (const std::exception& x) {
      first = error(exit_code::internal, x.what());
    } catch (...) {
      first = error(exit_code::internal, "unknown exception");
    }
  }
};

// Test-only fault injection (tests/faults/fault_table.sh, row mpi_throw):
// STICKSLIP_FAULT_INJECT=mpi_worker_throw_after_units:N makes a worker's
// main thread, outside its compute threads, throw once it has sent N results
// to rank 0, as a failed MPI call or allocation there would. Read by the
// workers of this backend once per spec they serve (per window of a large
// grid: the count starts again with each); any other value is an error,
// so that a test that misspells it cannot pass without its fault.
constexpr const char* fault_variable = "STICKSLIP_FAULT_INJECT";
std::optional<std::uint64_t> injected_throw_after_units() {
  const char* value = std::getenv(fault_variable);
  if (!value || !*value) return std::nullopt;
  constexpr std::string_view key = "mpi_worker_throw_after_units:";
  const std::string_view text(value);
  std::uint64_t n = 0;
  const char* end = text.data() + text.size();
  if (text.starts_with(key)) {
    const auto [p, ec] = std::from_chars(text.data() + key.size(), end, n);
    if (ec == std::errc() && p == end && p != text.data() + key.size()) return n;
  }
  throw error(exit_code::invalid_input,
              fmt::format("invalid {}: '{}' (allowed: mpi_worker_throw_after_units:N, a "
                          "test-only fault, N a whole number)",
                          fault_variable, text));
}

}  // namespace

bool launched_by_mpi() noexcept {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK",
                        "MPI_LOCALNRANKS", "HYDRA_CONTROL_FD"})
    if (std::getenv(v)) return true;
  return false;
}

session::session() {
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

session::~session() { MPI_Finalize(); }

void cancel(const session&) {
  std::uint64_t len = 0;
  MPI_Bcast(&len, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
}

// ---------------------------------------------------------------- rank 0
void coordinate(const session& ses, const sweep_spec& s, unsigned threads,
                ordered_merger& merger, const sweep_hooks& hooks) {
  {
    std::string spec = serialize(s);
    std::uint64_t len = spec.size();
    check(MPI_Bcast(&len, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
    check(MPI_Bcast(spec.data(), checked_size(spec.size()), MPI_BYTE, 0, MPI_COMM_WORLD),
          "MPI_Bcast");
  }
  const std::vector<std::uint64_t> todo = units_to_run(s, hooks);
  const std::uint64_t total = unit_count(s);
  std::mutex mu;  // guards next, failure, merger and the hooks
  std::size_t next = 0;
  failure_slot failure;

  auto take = [&](std::size_t n) {  // call with mu held
    std::vector<std::uint64_t> out;
    while (!failure.first && out.size() < n && next < todo.size()) {
      const auto i = todo[next++];
      if (merger.point_finished(unit_at(s, i).point)) continue;  // precision target met
      // Asked again at hand-out: the caller may have stopped wanting units
      // since the list was made (SIGTERM: finish what is out, hand out no more).
      if (hooks.wanted && !hooks.wanted(unit_at(s, i))) continue;
      out.push_back(i);
    }
    return out;
  };
  auto merge = [&](const work_unit& u, block_result&& r) {  // call with mu held
    if (failure.first) return;
    try {
      if (hooks.unit_done) hooks.unit_done(u, r);
      merger.add(u, std::move(r));
      if (hooks.progress) hooks.progress(merger.merged_units(), total);
    } catch (...) {
      failure.set(std::current_exception());
    }
  };

  // Local compute threads draw from the same list as the workers, a batch
  // of consecutive units at a time (simulate_units runs them together).
  const auto batch = static_cast<std::size_t>(units_per_batch(s));
  auto local = [&] {
    while (true) {
      std::vector<work_unit> units;
      {
        std::lock_guard lock(mu);
        for (auto i : take(batch)) units.push_back(unit_at(s, i));
      }
      if (units.empty()) return;
      try {
        auto results = simulate_units(s, units);
        std::lock_guard lock(mu);
        for (std::size_t c = 0; c < units.size(); ++c) merge(units[c], std::move(results[c]));
      } catch (...) {
        std::lock_guard lock(mu);
        failure.set(std::current_exception());
      }
    }
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned t = 0; t < resolve_threads(threads); ++t) pool.emplace_back(local);
  } catch (...) {  // a thread could not be created: end the sweep as a failed unit would
    std::lock_guard lock(mu);  // (the workers are told to stop; the threads made are joined)
    failure.set(std::current_exception());
  }

  // Serve the workers until each one is finished: told to stop with all of
  // its units returned, or failed (a failed worker sends nothing after that).
  struct worker_state {
    std::uint64_t outstanding = 0;  // units handed out, result not yet received
    bool told_stop = false, failed = false;
    [[nodiscard]] bool finished() const { return failed || (told_stop && outstanding == 0); }
  };
  std::vector<worker_state> workers(static_cast<std::size_t>(ses.size()));
  auto all_finished = [&] {
    for (std::size_t w = 1; w < workers.size(); ++w)
      if (!workers[w].finished()) return false;
    return true;
  };
  try {
    while (!all_finished()) {
      int flag = 0;
      MPI_Status st;
      check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
      if (!flag) {
        std::this_thread::sleep_for(poll_pause);
        continue;
      }
      const std::string msg = receive_bytes(st);
      auto& w = workers.at(static_cast<std::size_t>(st.MPI_SOURCE));
      if (st.MPI_TAG == request_tag) {
        detail::byte_reader r(msg);
        const auto n = r.u32("request size");
        std::vector<std::uint64_t> units;
        {
          std::lock_guard lock(mu);
          units = take(std::max<std::uint32_t>(1, n));
        }
        send_bytes(encode_indices(units), st.MPI_SOURCE, work_tag);
        w.outstanding += units.size();
        if (units.empty()) w.told_stop = true;
      } else if (st.MPI_TAG == result_tag) {
        if (w.outstanding > 0) --w.outstanding;
        std::lock_guard lock(mu);
        try {
          auto [u, r] = deserialize_unit_result(msg);
          check_block_shape(s, u, r);
          merge(u, std::move(r));
        } catch (...) {
          failure.set(std::current_exception());
        }
      } else if (st.MPI_TAG == failure_tag) {
        w.failed = true;
        detail::byte_reader r(msg);
        const auto code = static_cast<exit_code>(r.u32("exit code"));
        const auto text = r.str("message");
        std::lock_guard lock(mu);
        failure.set(std::make_exception_ptr(
            error(code, fmt::format("{} (on MPI rank {})", text, st.MPI_SOURCE))));
      }
    }
  } catch (...) {
    // MPI itself failed: the other ranks cannot be stopped cleanly.
    {
      std::lock_guard lock(mu);
      failure.set(std::current_exception());
    }
    for (auto& th : pool) th.join();
    MPI_Abort(MPI_COMM_WORLD, static_cast<int>(failure.first->code()));
  }
  for (auto& th : pool) th.join();
  if (failure.first) throw *failure.first;
}

// ---------------------------------------------------------------- workers
bool serve(const session&, unsigned threads) {
  std::uint64_t len = 0;
  check(MPI_Bcast(&len, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  if (len == 0) return false;  // rank 0 is done (or gave up before starting)
  std::string spec_bytes(len, '\0');
  check(MPI_Bcast(spec_bytes.data(), checked_size(len), MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
  const sweep_spec s = deserialize_sweep_spec(spec_bytes);
  const unsigned n_threads = resolve_threads(threads);
  const auto throw_after_units = injected_throw_after_units();

  std::mutex mu;
  std::condition_variable work_cv, main_cv;
  std::deque<std::uint64_t> queue;
  std::deque<std::string> outbox;
  unsigned busy = 0;
  bool shutdown = false;
  failure_slot failure;

  // Each compute thread takes up to a batch of queued units at a time
  // (consecutive blocks run together in simulate_units).
  const auto batch = static_cast<std::size_t>(units_per_batch(s));
  auto compute = [&] {
    std::unique_lock lock(mu);
    while (true) {
      work_cv.wait(lock, [&] { return shutdown || !queue.empty(); });
      if (queue.empty()) return;
      std::vector<work_unit> units;
      while (!queue.empty() && units.size() < batch) {
        units.push_back(unit_at(s, queue.front()));
        queue.pop_front();
      }
      busy += static_cast<unsigned>(units.size());
      lock.unlock();
      std::vector<std::string> out;
      std::exception_ptr err;
      try {
        auto results = simulate_units(s, units);
        for (std::size_t c = 0; c < units.size(); ++c) out.push_back(serialize(units[c], results[c]));
      } catch (...) {
        err = std::current_exception();
      }
      lock.lock();
      busy -= static_cast<unsigned>(units.size());
      if (err) {
        failure.set(err);
        queue.clear();
      } else {
        for (auto& m : out) outbox.push_back(std::move(m));
      }
      main_cv.notify_one();
    }
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned t = 0; t < n_threads; ++t) pool.emplace_back(compute);
  } catch (...) {  // threads could not be created: join those that were
    {
      std::lock_guard guard(mu);
      shutdown = true;
    }
    work_cv.notify_all();
    for (auto& th : pool) th.join();
    throw;
  }

  // The main thread does all MPI calls (MPI_THREAD_FUNNELED). Whatever way
  // it leaves, the compute threads are stopped and joined first: a thrown
  // error reaches serve_all (which reports it and aborts the job), never
  // std::terminate through a joinable std::thread.
  bool stopped = false;    // rank 0 said stop, or we failed
  bool fail_sent = false;  // after a failure nothing else is sent
  std::uint64_t results_sent = 0;
  std::unique_lock lock(mu);
  auto stop_compute_threads = [&] {
    if (!lock.owns_lock()) lock.lock();
    shutdown = true;
    queue.clear();  // units not started are not computed
    work_cv.notify_all();
    lock.unlock();
    for (auto& th : pool) th.join();
  };
  auto injected_fault = [&] {
    if (throw_after_units && results_sent >= *throw_after_units)
      throw error(exit_code::internal,
                  fmt::format("injected fault ({}=mpi_worker_throw_after_units:{}): the worker's "
                              "main thread throws after sending {} results",
                              fault_variable, *throw_after_units, results_sent));
  };
  try {
    while (true) {
      if (failure.first) outbox.clear();
      injected_fault();
      while (!outbox.empty()) {
        const std::string msg = std::move(outbox.front());
        outbox.pop_front();
        lock.unlock();
        send_bytes(msg, 0, result_tag);
        ++results_sent;
        injected_fault();
        lock.lock();
      }
      if (failure.first && !fail_sent) {
        detail::byte_writer w;
        w.u32(static_cast<std::uint32_t>(failure.first->code()));
        w.str(failure.first->what());
        lock.unlock();
        send_bytes(w.take(), 0, failure_tag);
        lock.lock();
        stopped = fail_sent = true;
        queue.clear();  // units received while failing are not computed
      }
      // Keep every thread busy plus one batch queued, so no thread waits for
      // a round trip; not more, so the tail stays balanced.
      const std::size_t outstanding = queue.size() + busy;
      const std::size_t wanted = (n_threads + 1) * batch;
      if (!stopped && outstanding < wanted) {
        detail::byte_writer w;
        w.u32(static_cast<std::uint32_t>(wanted - outstanding));
        lock.unlock();
        send_bytes(w.take(), 0, request_tag);
        MPI_Status st;
        check(MPI_Probe(0, work_tag, MPI_COMM_WORLD, &st), "MPI_Probe");
        const auto units = decode_indices(receive_bytes(st));
        lock.lock();
        if (units.empty()) stopped = true;
        for (auto i : units) queue.push_back(i);
        work_cv.notify_all();
        continue;
      }
      if (stopped && queue.empty() && busy == 0 && (outbox.empty() || fail_sent)) break;
      main_cv.wait_for(lock, std::chrono::milliseconds(5));
    }
  } catch (...) {
    stop_compute_threads();
    throw;
  }
  stop_compute_threads();
  return true;
}

void serve_all(const session& ses, unsigned threads) {
  // A failure outside the compute threads (an MPI call, thread creation, a
  // spec that does not deserialize) cannot be reported to rank 0 through the
  // protocol, and rank 0 would wait for this rank forever: say why and abort
  // the whole job instead of leaving it hanging.
  try {
    while (serve(ses, threads)) {
    }
  } catch (const std::exception& x) {
    int rank = -1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    const auto* e = dynamic_cast<const error*>(&x);
    std::fprintf(stderr, "stickslip: error: MPI rank %d: %s; aborting the job\n", rank, x.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, e ? static_cast<int>(e->code()) : 1);
  }
}

}  // namespace stickslip::mpi
