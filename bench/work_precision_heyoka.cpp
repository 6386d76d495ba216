// Work-precision benchmark, heyoka's half (a peer, never a dependency: the
// driver bench/work_precision.sh builds this only when /opt/heyoka exists).
// The same four systems, initial states, tolerances and final times as
// bench/work_precision.c, the vector fields from H by heyoka's own diff (the
// path hamlie takes), taylor_adaptive<double> with kw::tol = tol.
//
// Rows (CSV, as work_precision.c): heyoka,system,T,tol,order,steps,ms,jit_ms,z...
// ms: propagate_until(T) alone, CPU time, the best of reps runs; jit_ms: constructing
// the integrator (JIT compilation), once per tolerance.
//
// Build (the driver does): g++ -O2 -std=c++20 -I/opt/heyoka/include
//   work_precision_heyoka.cpp -L/opt/heyoka/lib -Wl,-rpath,/opt/heyoka/lib -lheyoka -lfmt
// Usage: work_precision_heyoka reps T-list tol-list [system -1|0..3]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include <heyoka/heyoka.hpp>

namespace hy = heyoka;
using hy::expression;
using namespace hy::literals;

namespace
{

const char *const names[4] = {"oscillator", "pendulum", "henon-heiles", "kepler"};
const std::vector<double> initial[4] = {
    {1., 0.}, {1.3, 0.}, {0.1, -0.1, 0.05, 0.1}, {0.5, 0., 0., 1.7320508075688772}};

// z' = (dH/dp, -dH/dq), state order (q..., p...) as hamlie's
std::vector<std::pair<expression, expression>> make_sys(int which)
{
    if (which <= 1) {
        auto [q, p] = hy::make_vars("q", "p");
        expression H = which == 0 ? (p * p + q * q) / 2_dbl : p * p / 2_dbl - hy::cos(q);
        return {hy::prime(q) = hy::diff(H, p), hy::prime(p) = -hy::diff(H, q)};
    }
    auto [x, y, px, py] = hy::make_vars("x", "y", "px", "py");
    expression H = which == 2 ? (px * px + py * py) / 2_dbl + (x * x + y * y) / 2_dbl + x * x * y -
                                    y * y * y / 3_dbl
                              : (px * px + py * py) / 2_dbl - 1_dbl / hy::sqrt(x * x + y * y);
    return {hy::prime(x) = hy::diff(H, px), hy::prime(y) = hy::diff(H, py),
            hy::prime(px) = -hy::diff(H, x), hy::prime(py) = -hy::diff(H, y)};
}

// CPU time of the process (see work_precision.c: the machine may be shared)
double now()
{
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::vector<double> parse_list(const char *s)
{
    std::vector<double> v;
    std::string str(s);
    for (std::size_t pos = 0; pos <= str.size();) {
        auto c = str.find(',', pos);
        if (c == std::string::npos)
            c = str.size();
        v.push_back(std::atof(str.substr(pos, c - pos).c_str()));
        pos = c + 1;
    }
    return v;
}

void run(int s, double tol, const std::vector<double> &Ts, int reps)
{
    const double c0 = now();
    hy::taylor_adaptive<double> ta{make_sys(s), initial[s], hy::kw::tol = tol};
    const double jit_ms = 1e3 * (now() - c0);
    for (double T : Ts) {
        double best = INFINITY;
        std::size_t nsteps = 0;
        for (int r = 0; r < reps; ++r) {
            ta.set_time(0.);
            std::copy(initial[s].begin(), initial[s].end(), ta.get_state_data());
            const double t0 = now();
            auto res = ta.propagate_until(T);
            best = std::min(best, now() - t0);
            if (std::get<0>(res) != hy::taylor_outcome::time_limit) {
                std::fprintf(stderr, "heyoka %s tol %g: outcome %d\n", names[s], tol,
                             static_cast<int>(std::get<0>(res)));
                return;
            }
            nsteps = std::get<3>(res);
        }
        std::printf("heyoka,%s,%g,%g,%u,%zu,%.4f,%.2f", names[s], T, tol, ta.get_order(), nsteps,
                    1e3 * best, jit_ms);
        for (double z : ta.get_state())
            std::printf(",%.17g", z);
        std::printf("\n");
        std::fflush(stdout);
    }
}

} // namespace

int main(int argc, char **argv)
{
    const int reps = std::max(1, argc > 1 ? std::atoi(argv[1]) : 3);
    const auto Ts = parse_list(argc > 2 ? argv[2] : "1e4,1e5");
    const auto tols =
        parse_list(argc > 3 ? argv[3] : "1e-9,1e-10,1e-11,1e-12,1e-13,1e-14,1e-15,1e-16");
    const int only = argc > 4 ? std::atoi(argv[4]) : -1;
    for (int s = 0; s < 4; ++s)
        if (only < 0 || s == only)
            for (double tol : tols)
                run(s, tol, Ts, reps);
    return 0;
}
