// heyoka's half of bench/process_lie.sh: one whole process that does what
// `hamlie run -H H --scheme lie --tol TOL --t T --init ... --json` does, so
// that the two processes can be timed side by side (start-up, JIT
// compilation, integration, output).  A peer, never a dependency: the driver
// builds this only when /opt/heyoka exists.
//
// What hamlie's command does, and so this program: the vector field from H
// by differentiation (heyoka's own diff), the adaptive Taylor integrator at
// tolerance tol from the initial state to T, the state at the 1001 rows
// t_k = k T/1000 (hamlie's default row spacing; propagate_grid here, the
// dense output there), H at every row for max |H - H0|, and a JSON summary
// of the final state and the energy error on standard output.
//
// Build (the driver does): g++ -O2 -std=c++20 -I/opt/heyoka/include
//   process_lie_heyoka.cpp -L/opt/heyoka/lib -Wl,-rpath,/opt/heyoka/lib -lheyoka -lfmt
// Usage: process_lie_heyoka SYSTEM T TOL
//   SYSTEM: oscillator | pendulum | henon-heiles | kepler (the initial
//   states of bench/work_precision.c)

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <heyoka/heyoka.hpp>

namespace hy = heyoka;
using hy::expression;
using namespace hy::literals;

namespace
{

constexpr int rows = 1000;

struct system_def {
    const char *name;
    std::vector<const char *> vars; // q..., p...
    std::vector<double> init;
};

const system_def systems[4] = {
    {"oscillator", {"q", "p"}, {1., 0.}},
    {"pendulum", {"q", "p"}, {1.3, 0.}},
    {"henon-heiles", {"x", "y", "px", "py"}, {0.1, -0.1, 0.05, 0.1}},
    {"kepler", {"x", "y", "px", "py"}, {0.5, 0., 0., 1.7320508075688772}},
};

// H as an expression of the state's variables (the same formulas as the
// hamlie command's -H)
expression hamiltonian(int which, const std::vector<expression> &v)
{
    switch (which) {
    case 0:
        return (v[1] * v[1] + v[0] * v[0]) / 2_dbl;
    case 1:
        return v[1] * v[1] / 2_dbl - hy::cos(v[0]);
    case 2:
        return (v[2] * v[2] + v[3] * v[3]) / 2_dbl + (v[0] * v[0] + v[1] * v[1]) / 2_dbl +
               v[0] * v[0] * v[1] - v[1] * v[1] * v[1] / 3_dbl;
    default:
        return (v[2] * v[2] + v[3] * v[3]) / 2_dbl - 1_dbl / hy::sqrt(v[0] * v[0] + v[1] * v[1]);
    }
}

// H at a state, in double (for max |H - H0| over the rows)
double energy(int which, const double *z)
{
    switch (which) {
    case 0:
        return (z[1] * z[1] + z[0] * z[0]) / 2;
    case 1:
        return z[1] * z[1] / 2 - std::cos(z[0]);
    case 2:
        return (z[2] * z[2] + z[3] * z[3]) / 2 + (z[0] * z[0] + z[1] * z[1]) / 2 +
               z[0] * z[0] * z[1] - z[1] * z[1] * z[1] / 3;
    default:
        return (z[2] * z[2] + z[3] * z[3]) / 2 - 1 / std::sqrt(z[0] * z[0] + z[1] * z[1]);
    }
}

// z' = (dH/dp, -dH/dq)
std::vector<std::pair<expression, expression>> equations(int which, const system_def &s)
{
    std::vector<expression> v;
    for (const char *name : s.vars)
        v.emplace_back(hy::variable(name));
    const expression H = hamiltonian(which, v);
    const std::size_t n = v.size() / 2;
    std::vector<std::pair<expression, expression>> eqs;
    for (std::size_t i = 0; i < n; ++i)
        eqs.push_back(hy::prime(v[i]) = hy::diff(H, v[n + i]));
    for (std::size_t i = 0; i < n; ++i)
        eqs.push_back(hy::prime(v[n + i]) = -hy::diff(H, v[i]));
    return eqs;
}

int system_index(const char *name)
{
    for (int i = 0; i < 4; ++i)
        if (std::strcmp(name, systems[i].name) == 0)
            return i;
    return -1;
}

} // namespace

int main(int argc, char **argv)
{
    const int which = argc == 4 ? system_index(argv[1]) : -1;
    if (which < 0) {
        std::fprintf(stderr,
                     "usage: process_lie_heyoka oscillator|pendulum|henon-heiles|kepler T TOL\n");
        return 2;
    }
    const system_def &s = systems[which];
    const double T = std::atof(argv[2]), tol = std::atof(argv[3]);
    hy::taylor_adaptive<double> ta{equations(which, s), s.init, hy::kw::tol = tol};
    std::vector<double> grid(rows + 1);
    for (int k = 0; k <= rows; ++k)
        grid[k] = static_cast<double>(k) * (T / rows);
    auto res = ta.propagate_grid(grid);
    if (std::get<0>(res) != hy::taylor_outcome::time_limit) {
        std::fprintf(stderr, "heyoka: outcome %d\n", static_cast<int>(std::get<0>(res)));
        return 2;
    }
    const std::vector<double> &out = std::get<5>(res);
    const std::size_t dim = s.init.size();
    const double H0 = energy(which, s.init.data());
    double max_dH = 0;
    for (int k = 0; k <= rows; ++k)
        max_dH = std::fmax(max_dH, std::fabs(energy(which, &out[k * dim]) - H0));
    const double *zf = &out[rows * dim];
    std::printf("{\"system\": \"%s\", \"t\": %.17g, \"tol\": %.17g, \"final_state\": {", s.name, T,
                tol);
    for (std::size_t i = 0; i < dim; ++i)
        std::printf("%s\"%s\": %.17g", i ? ", " : "", s.vars[i], zf[i]);
    std::printf(
        "}, \"H0\": %.17g, \"H_final\": %.17g, \"max_abs_dH\": %.17g, \"taylor_steps\": %zu, "
        "\"order\": %u}\n",
        H0, energy(which, zf), max_dH, std::get<3>(res), ta.get_order());
    return 0;
}
