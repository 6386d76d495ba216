// The batch benchmark, heyoka's half (a peer, never a dependency: the
// driver bench/taylor_batch.sh builds this only when /opt/heyoka exists).
// The same ensemble as bench/taylor_batch.c: Henon-Heiles, tol 1e-15,
// t = 1000, members seeded on x = 0 at E = 1/12, 1/8, 1/6 (the same seed
// function), the vector field from H by heyoka's own diff:
//   heyoka-scalar   taylor_adaptive<double>, one member at a time
//   heyoka-batch-L  taylor_adaptive_batch<double>, L members a batch (2, 4, 8)
// Each integrator is made once (JIT outside the timing: setup_ms) and
// reused for every member or batch; CPU time, the best of reps.
// CSV as taylor_batch.c: mode,members,T,cpu_s,members_per_s,steps,steps_per_s,setup_ms,identical
// (identical: "-", heyoka's arithmetic is its own; max_dH, the largest
// energy error of a member, is printed on stderr as a sanity check).
//
// Build (the driver does): g++ -O2 -DNDEBUG -std=c++20 -I/opt/heyoka/include
//   taylor_batch_heyoka.cpp -L/opt/heyoka/lib -Wl,-rpath,/opt/heyoka/lib -lheyoka -lfmt
//   -lboost_serialization
// Usage: taylor_batch_heyoka [members 64] [T 1000] [reps 3] [mode
// all|heyoka-scalar|heyoka-batch-4...]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include <heyoka/heyoka.hpp>

namespace hy = heyoka;
using hy::expression;
using namespace hy::literals;

namespace
{

constexpr double tol = 1e-15;

double cpu()
{
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// taylor_batch.c's seed, word for word
void seed(double *z, int i, int B)
{
    static const double E[3] = {1.0 / 12, 1.0 / 8, 1.0 / 6};
    int g = i % 3, j = i / 3, nj = (B + 2 - g) / 3;
    double e = E[g];
    double lo = -0.95 * (g == 0 ? 0.36 : g == 1 ? 0.42 : 0.48), hi = 0.95 * (g == 2 ? 0.72 : 0.5);
    double y = nj > 1 ? lo + (hi - lo) * j / (nj - 1) : 0.1;
    double u = 2 * e - y * y + 2 * y * y * y / 3;
    z[0] = 0;
    z[1] = y;
    z[2] = std::sqrt(u > 0 ? u : 0);
    z[3] = 0;
}

double energy(const double *z)
{
    double x = z[0], y = z[1];
    return (z[2] * z[2] + z[3] * z[3]) / 2 + (x * x + y * y) / 2 + x * x * y - y * y * y / 3;
}

std::vector<std::pair<expression, expression>> henon_heiles()
{
    auto [x, y, px, py] = hy::make_vars("x", "y", "px", "py");
    expression H =
        (px * px + py * py) / 2_dbl + (x * x + y * y) / 2_dbl + x * x * y - y * y * y / 3_dbl;
    return {hy::prime(x) = hy::diff(H, px), hy::prime(y) = hy::diff(H, py),
            hy::prime(px) = -hy::diff(H, x), hy::prime(py) = -hy::diff(H, y)};
}

struct result {
    double cpu = INFINITY, setup_ms = 0, max_dH = 0;
    long steps = 0;
};

result run_scalar(int B, double T)
{
    result r;
    std::vector<double> z(4);
    seed(z.data(), 0, B);
    double c0 = cpu();
    hy::taylor_adaptive<double> ta{henon_heiles(), z, hy::kw::tol = tol};
    r.setup_ms = 1e3 * (cpu() - c0);
    c0 = cpu();
    std::vector<double> out(4 * static_cast<std::size_t>(B));
    for (int i = 0; i < B; ++i) {
        seed(ta.get_state_data(), i, B);
        ta.set_time(0.);
        auto res = ta.propagate_until(T);
        r.steps += static_cast<long>(std::get<3>(res));
        std::copy(ta.get_state().begin(), ta.get_state().end(), out.begin() + 4 * i);
    }
    r.cpu = cpu() - c0;
    for (int i = 0; i < B; ++i) {
        double z0[4];
        seed(z0, i, B);
        r.max_dH = std::max(r.max_dH, std::fabs(energy(&out[4 * i]) - energy(z0)));
    }
    return r;
}

// members in batches of L (the last padded with member 0's copy, not counted)
result run_batch(int B, double T, unsigned L)
{
    result r;
    std::vector<double> init(4 * L);
    double z[4];
    for (unsigned l = 0; l < L; ++l) {
        seed(z, 0, B);
        for (int c = 0; c < 4; ++c)
            init[c * L + l] = z[c];
    }
    double c0 = cpu();
    hy::taylor_adaptive_batch<double> ta{henon_heiles(), init, L, hy::kw::tol = tol};
    r.setup_ms = 1e3 * (cpu() - c0);
    std::vector<double> out(4 * static_cast<std::size_t>(B));
    c0 = cpu();
    for (int b0 = 0; b0 < B; b0 += static_cast<int>(L)) {
        double *s = ta.get_state_data();
        for (unsigned l = 0; l < L; ++l) {
            int i = b0 + static_cast<int>(l) < B ? b0 + static_cast<int>(l) : 0;
            seed(z, i, B);
            for (int c = 0; c < 4; ++c)
                s[c * L + l] = z[c];
        }
        ta.set_time(0.);
        ta.propagate_until(T);
        const auto &pr = ta.get_propagate_res();
        for (unsigned l = 0; l < L && b0 + static_cast<int>(l) < B; ++l) {
            r.steps += static_cast<long>(std::get<3>(pr[l]));
            for (int c = 0; c < 4; ++c)
                out[4 * (b0 + l) + c] = ta.get_state()[c * L + l];
        }
    }
    r.cpu = cpu() - c0;
    for (int i = 0; i < B; ++i) {
        seed(z, i, B);
        r.max_dH = std::max(r.max_dH, std::fabs(energy(&out[4 * i]) - energy(z)));
    }
    return r;
}

} // namespace

int main(int argc, char **argv)
{
    const int B = argc > 1 ? std::atoi(argv[1]) : 64;
    const double T = argc > 2 ? std::atof(argv[2]) : 1000;
    const int reps = std::max(1, argc > 3 ? std::atoi(argv[3]) : 3);
    const std::string only = argc > 4 ? argv[4] : "all";
    const char *const modes[] = {"heyoka-scalar", "heyoka-batch-2", "heyoka-batch-4",
                                 "heyoka-batch-8"};
    for (const char *m : modes) {
        if (only != "all" && only != m)
            continue;
        result best;
        for (int r = 0; r < reps; ++r) {
            result x =
                std::strcmp(m, "heyoka-scalar") == 0
                    ? run_scalar(B, T)
                    : run_batch(B, T,
                                static_cast<unsigned>(std::atoi(m + std::strlen("heyoka-batch-"))));
            if (x.cpu < best.cpu)
                best = x;
        }
        std::printf("%s,%d,%g,%.4f,%.1f,%ld,%.0f,%.1f,-\n", m, B, T, best.cpu, B / best.cpu,
                    best.steps, static_cast<double>(best.steps) / best.cpu, best.setup_ms);
        std::fprintf(stderr, "%s: max |H - H0| over the members %.3g\n", m, best.max_dH);
        std::fflush(stdout);
    }
    return 0;
}
