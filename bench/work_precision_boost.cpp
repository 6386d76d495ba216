// Work-precision benchmark, Boost.Odeint's half: runge_kutta_fehlberg78 with
// step-size control (make_controlled, abs = rel = tol) through
// integrate_adaptive, on the four systems of bench/work_precision.c, the
// vector fields written by hand.  Header-only (Debian libboost-dev); the
// driver bench/work_precision.sh builds it when the header is found.
//
// Rows (CSV, as work_precision.c): rkf78,system,T,tol,8,steps,ms,0,z...
// ms: the integration alone, CPU time, the best of reps runs; steps: accepted steps.
// Usage: work_precision_boost reps T-list tol-list [system -1|0..3]

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

namespace ode = boost::numeric::odeint;

namespace
{

using state = std::vector<double>;

const char *const names[4] = {"oscillator", "pendulum", "henon-heiles", "kepler"};
const state initial[4] = {
    {1., 0.}, {1.3, 0.}, {0.1, -0.1, 0.05, 0.1}, {0.5, 0., 0., 1.7320508075688772}};

void rhs(int s, const state &z, state &f)
{
    switch (s) {
    case 0:
        f[0] = z[1];
        f[1] = -z[0];
        break;
    case 1:
        f[0] = z[1];
        f[1] = -std::sin(z[0]);
        break;
    case 2:
        f[0] = z[2];
        f[1] = z[3];
        f[2] = -z[0] - 2 * z[0] * z[1];
        f[3] = -z[1] - z[0] * z[0] + z[1] * z[1];
        break;
    default: {
        const double r2 = z[0] * z[0] + z[1] * z[1], r3 = r2 * std::sqrt(r2);
        f[0] = z[2];
        f[1] = z[3];
        f[2] = -z[0] / r3;
        f[3] = -z[1] / r3;
    }
    }
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

void run(int s, double T, double tol, int reps)
{
    double best = INFINITY;
    std::size_t steps = 0;
    state z;
    for (int r = 0; r < reps; ++r) {
        z = initial[s];
        auto stepper = ode::make_controlled(tol, tol, ode::runge_kutta_fehlberg78<state>());
        const double t0 = now();
        steps = ode::integrate_adaptive(
            stepper, [s](const state &x, state &dx, double) { rhs(s, x, dx); }, z, 0.0, T, 1e-3);
        best = std::min(best, now() - t0);
    }
    std::printf("rkf78,%s,%g,%g,8,%zu,%.4f,0", names[s], T, tol, steps, 1e3 * best);
    for (double v : z)
        std::printf(",%.17g", v);
    std::printf("\n");
    std::fflush(stdout);
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
            for (double T : Ts)
                for (double tol : tols)
                    run(s, T, tol, reps);
    return 0;
}
