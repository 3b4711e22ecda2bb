#pragma once
// Terminal progress bar for renders: percentage, elapsed time and ETA on one line of stderr,
// redrawn in place with '\r'. Silent when stderr is not a terminal, so logs and CI output
// stay clean.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace snell {

/// One progress line, e.g. "render [#####-----]  50.0%  elapsed 1m02s  ETA 1m02s".
/// `fraction` is clamped to [0,1]; `eta_seconds` < 0 prints "ETA --" (unknown).
/// `bar_width` is the number of characters between the brackets.
std::string format_progress_line(const std::string& label, double fraction, double elapsed_seconds, double eta_seconds,
                                 int bar_width = 30);

/// Human-readable duration: "42s", "3m07s", "2h05m" (negative or NaN: "--").
std::string format_duration(double seconds);

/// Thread-safe progress bar. Any thread may call add()/update(); at most one redraw per
/// 100 ms happens, by whichever caller finds it due (others return at once).
class ProgressBar {
public:
    /// Work-count mode: progress is (units added) / total.
    ProgressBar(std::string label, uint64_t total);
    /// Time-budget mode: progress is elapsed / seconds (for time-limited renders).
    static ProgressBar for_time(std::string label, double seconds);
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;
    /// Calls finish() if it was not called.
    ~ProgressBar();

    /// Records `done` more units of work (ignored in time mode) and redraws if due.
    void add(uint64_t done);
    /// Redraws if due without adding work (useful in time mode).
    void update() { add(0); }
    /// Draws the final state and ends the line. Idempotent.
    void finish();

    /// Progress in [0,1].
    double fraction() const;
    /// Units added so far (work-count mode).
    uint64_t done() const { return m_done.load(std::memory_order_relaxed); }
    /// Seconds since construction.
    double elapsed() const;
    /// Whether anything is printed (stderr is a TTY). Tests may force it.
    bool enabled() const { return m_enabled; }
    void set_enabled(bool on) { m_enabled = on; }
    /// Lines mode (render farms, issue 27): instead of the bar, one line of JSON per update on
    /// stdout, at most one a second, and a last one when finished:
    ///   {"progress": 0.4213, "elapsed_s": 12.3, "eta_s": 16.9, "done": false}
    /// ("eta_s" is null while unknown). Enabled whether or not stderr is a terminal.
    void set_lines(bool on) {
        m_lines = on;
        if (on) m_enabled = true;
    }

    /// Also keeps the fraction done in `sink` (may be null) at every add() and at finish(), for a
    /// caller that draws progress its own way.
    void set_fraction_sink(std::atomic<double>* sink) { m_sink = sink; }

private:
    using Clock = std::chrono::steady_clock;
    ProgressBar(std::string label, uint64_t total, double budget_seconds);
    void draw(bool final_line);

    std::string m_label;
    uint64_t m_total;
    double m_budget;  // > 0: time mode
    Clock::time_point m_start;
    std::atomic<uint64_t> m_done{0};
    std::atomic<int64_t> m_last_draw_ns{0};  // since m_start
    std::atomic<bool> m_finished{false};
    std::mutex m_draw_mutex;
    size_t m_last_len = 0;  // guarded by m_draw_mutex
    bool m_enabled;
    bool m_lines = false;
    std::atomic<double>* m_sink = nullptr;
};

/// The JSON line of lines mode.
std::string format_progress_json(double fraction, double elapsed_seconds, double eta_seconds, bool done);

}  // namespace snell
