#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace snell {

namespace {
constexpr int64_t kRedrawIntervalNs = 100'000'000;  // ~10 redraws per second
constexpr int64_t kLineIntervalNs = 1'000'000'000;  // lines mode: one a second
}  // namespace

std::string format_duration(double s) {
    if (!(s >= 0) || std::isinf(s)) return "--";
    const long t = std::lround(s);
    char buf[32];
    if (t < 60)
        std::snprintf(buf, sizeof buf, "%lds", t);
    else if (t < 3600)
        std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
    else
        std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
    return buf;
}

std::string format_progress_line(const std::string& label, double fraction, double elapsed, double eta, int bar_width) {
    const double f = std::isnan(fraction) ? 0.0 : std::clamp(fraction, 0.0, 1.0);
    const int filled = std::clamp(int(f * bar_width), 0, bar_width);
    std::string line = label;
    line += " [";
    line.append(size_t(filled), '#');
    line.append(size_t(bar_width - filled), '-');
    char pct[16];
    std::snprintf(pct, sizeof pct, "] %5.1f%%", 100.0 * f);
    line += pct;
    line += "  elapsed " + format_duration(elapsed);
    line += "  ETA " + format_duration(eta);
    return line;
}

std::string format_progress_json(double fraction, double elapsed_seconds, double eta_seconds, bool done) {
    char buf[160];
    const double f = std::clamp(fraction == fraction ? fraction : 0.0, 0.0, 1.0);
    if (eta_seconds >= 0)
        std::snprintf(buf, sizeof(buf), "{\"progress\": %.4f, \"elapsed_s\": %.3f, \"eta_s\": %.3f, \"done\": %s}", f,
                      elapsed_seconds, eta_seconds, done ? "true" : "false");
    else
        std::snprintf(buf, sizeof(buf), "{\"progress\": %.4f, \"elapsed_s\": %.3f, \"eta_s\": null, \"done\": %s}", f,
                      elapsed_seconds, done ? "true" : "false");
    return buf;
}

ProgressBar::ProgressBar(std::string label, uint64_t total) : ProgressBar(std::move(label), total, 0.0) {}

ProgressBar::ProgressBar(std::string label, uint64_t total, double budget)
    : m_label(std::move(label)),
      m_total(total),
      m_budget(budget),
      m_start(Clock::now()),
      m_enabled(isatty(fileno(stderr)) != 0) {
    m_last_draw_ns.store(-kRedrawIntervalNs, std::memory_order_relaxed);  // first add() draws
}

ProgressBar ProgressBar::for_time(std::string label, double seconds) {
    // Guaranteed copy elision: the non-movable bar is built in the caller's storage.
    return ProgressBar(std::move(label), 0, std::max(seconds, 1e-9));
}

ProgressBar::~ProgressBar() { finish(); }

double ProgressBar::elapsed() const { return std::chrono::duration<double>(Clock::now() - m_start).count(); }

double ProgressBar::fraction() const {
    if (m_budget > 0) return std::min(1.0, elapsed() / m_budget);
    if (m_total == 0) return 1.0;
    return std::min(1.0, double(done()) / double(m_total));
}

void ProgressBar::add(uint64_t n) {
    if (n) m_done.fetch_add(n, std::memory_order_relaxed);
    if (m_sink) m_sink->store(fraction(), std::memory_order_relaxed);
    if (!m_enabled || m_finished.load(std::memory_order_relaxed)) return;
    const int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - m_start).count();
    int64_t last = m_last_draw_ns.load(std::memory_order_relaxed);
    if (now - last < (m_lines ? kLineIntervalNs : kRedrawIntervalNs)) return;
    // One thread wins the right to draw this frame; the others carry on rendering.
    if (!m_last_draw_ns.compare_exchange_strong(last, now, std::memory_order_relaxed)) return;
    std::unique_lock<std::mutex> lock(m_draw_mutex, std::try_to_lock);
    if (lock.owns_lock() && !m_finished.load(std::memory_order_relaxed)) draw(false);
}

void ProgressBar::finish() {
    if (m_finished.exchange(true)) return;
    if (m_sink) m_sink->store(fraction(), std::memory_order_relaxed);
    if (!m_enabled) return;
    std::lock_guard<std::mutex> lock(m_draw_mutex);
    draw(true);
}

void ProgressBar::draw(bool final_line) {
    const double t = elapsed();
    const double f = fraction();
    double eta;
    if (m_budget > 0)
        eta = std::max(0.0, m_budget - t);
    else if (f >= 1.0)
        eta = 0.0;
    else if (f > 0.0)
        eta = t * (1.0 - f) / f;  // constant-rate extrapolation
    else
        eta = -1.0;  // unknown until some work is done
    if (m_lines) {
        std::fputs(format_progress_json(f, t, eta, final_line).c_str(), stdout);
        std::fputc('\n', stdout);
        std::fflush(stdout);
        return;
    }
    std::string line = format_progress_line(m_label, f, t, eta);
    // Pad with spaces so a shorter line fully overwrites the previous one.
    const size_t len = line.size();
    if (len < m_last_len) line.append(m_last_len - len, ' ');
    m_last_len = len;
    std::fputc('\r', stderr);
    std::fputs(line.c_str(), stderr);
    if (final_line) std::fputc('\n', stderr);
    std::fflush(stderr);
}

}  // namespace snell
