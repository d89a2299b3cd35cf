// Erosion and sedimentation laws (the design note is in surface_laws.hpp).
//
// Diffusion: backward Euler, (I − r L) h' = h + r g with r = κ dS / Δx², L
// the three-point Laplacian and g the fixed ends' ghost heights (zero for
// closed ends, whose end rows have diagonal 1 + r instead of 1 + 2r). The
// matrix is a strictly diagonally dominant M-matrix, so the Thomas sweep
// needs no pivoting and h' is a convex combination of h and g (monotone).
// With closed ends every column of the matrix sums to 1, so Σ h' = Σ h; the
// round-off of the solve in that sum is put back as a uniform shift.
#include "orodem/analysis/surface_laws.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace orodem {

namespace {

void require_finite_nonneg(double v, const char* what) {
    if (!std::isfinite(v) || v < 0.0)
        throw std::invalid_argument(std::string(what) + " must be finite and >= 0, got " + std::to_string(v));
}

void require_same_size(std::size_t a, std::size_t b, const char* what) {
    if (a != b) throw std::invalid_argument(std::string(what) + ": size mismatch with the profile");
}

void require_step(double dx, double dS) {
    if (!std::isfinite(dx) || dx <= 0.0) throw std::invalid_argument("surface: column width must be > 0");
    require_finite_nonneg(dS, "surface: shortening increment dS");
}

/// The rule of take_whole_particles: the next particle of area A is due
/// while the remainder r reaches half of it (rounding to the nearest whole).
bool whole_particle_due(double r, double area) { return r >= 0.5 * area; }

/// Erosion of a rate law: rate_c dS Δx, clipped to the column's h⁺ Δx.
double clipped_erosion(double rate, double h, double dx, double dS) {
    return std::min(rate * dS, std::max(h, 0.0)) * dx;
}

/// Slope law: E_c = K × (the column's share of the interfaces' |Δh⁺|) / Δx.
void slope_request(double K, std::span<const double> h, double dx, double dS, std::span<double> erode) {
    const std::size_t n = h.size();
    for (std::size_t c = 0; c < n; ++c) erode[c] = 0.0;  // the shares [h0] first
    for (std::size_t c = 0; c + 1 < n; ++c) {
        const double a = std::max(h[c], 0.0), b = std::max(h[c + 1], 0.0);
        const double jump = std::abs(b - a);
        if (a > 0.0 && b > 0.0) {
            erode[c] += 0.5 * jump;
            erode[c + 1] += 0.5 * jump;
        } else if (a > 0.0) {
            erode[c] += jump;
        } else if (b > 0.0) {
            erode[c + 1] += jump;
        }
    }
    for (std::size_t c = 0; c < n; ++c) erode[c] = clipped_erosion(K * erode[c] / dx, h[c], dx, dS);
}

/// One backward-Euler diffusion step into ws.h_new (Thomas algorithm).
void diffuse(const SurfaceLaw& law, std::span<const double> h, double dx, double dS, SurfaceWorkspace& ws) {
    const std::size_t n = h.size();
    ws.h_new.resize(n);
    ws.c_prime.resize(n);
    std::vector<double>& d = ws.h_new;  // the right-hand side, swept into the solution
    std::vector<double>& cp = ws.c_prime;
    const double r = law.kappa * dS / (dx * dx);
    const bool fixed = law.ends == DiffusionEnds::fixed;
    // Row c: −r h'_{c−1} + diag_c h'_c − r h'_{c+1} = h_c (+ r g at a fixed end).
    auto diag = [&](std::size_t c) {
        double v = 1.0 + 2.0 * r;
        if (!fixed && c == 0) v -= r;
        if (!fixed && c + 1 == n) v -= r;
        return v;
    };
    for (std::size_t c = 0; c < n; ++c) d[c] = h[c];
    if (fixed) {
        d[0] += r * law.h_left;
        d[n - 1] += r * law.h_right;
    }
    // Forward sweep: sub- and super-diagonals are −r.
    double m = diag(0);
    cp[0] = -r / m;
    d[0] /= m;
    for (std::size_t c = 1; c < n; ++c) {
        m = diag(c) + r * cp[c - 1];
        cp[c] = -r / m;
        d[c] = (d[c] + r * d[c - 1]) / m;
    }
    for (std::size_t c = n - 1; c-- > 0;) d[c] -= cp[c] * d[c + 1];
    if (!fixed) {
        // The exact solution keeps Σ h; the sweep's round-off in it (relative
        // ε r: the constant mode's pivot is O(1) among O(r) ones) is put back
        // as a uniform shift, so erosion and deposition balance at any dS.
        double before = 0.0, after = 0.0;
        for (std::size_t c = 0; c < n; ++c) {
            before += h[c];
            after += d[c];
        }
        const double shift = (before - after) / static_cast<double>(n);
        for (std::size_t c = 0; c < n; ++c) d[c] += shift;
    }
}

}  // namespace

void check_surface_law(const SurfaceLaw& law) {
    switch (law.kind) {
        case SurfaceLawKind::none: break;
        case SurfaceLawKind::elevation: require_finite_nonneg(law.k, "elevation law k"); break;
        case SurfaceLawKind::slope: require_finite_nonneg(law.K, "slope law K"); break;
        case SurfaceLawKind::uniform: require_finite_nonneg(law.e_dot, "uniform law rate"); break;
        case SurfaceLawKind::cap:
            if (!std::isfinite(law.H_c)) throw std::invalid_argument("cap height H_c must be finite");
            break;
        case SurfaceLawKind::diffusion:
            require_finite_nonneg(law.kappa, "diffusivity kappa");
            if (law.ends == DiffusionEnds::fixed && !(std::isfinite(law.h_left) && std::isfinite(law.h_right)))
                throw std::invalid_argument("diffusion: fixed end heights must be finite");
            break;
    }
}

void check_sediment_rule(const SedimentRule& rule) {
    if (!std::isfinite(rule.base_level)) throw std::invalid_argument("sedimentation base level must be finite");
    if (!rule.at_once) require_finite_nonneg(rule.rate, "sedimentation rate");
}

SurfaceTotals surface_request(const SurfaceLaw& law, std::span<const double> h, double dx, double dS,
                              std::span<double> erode, std::span<double> deposit, SurfaceWorkspace& ws) {
    require_same_size(erode.size(), h.size(), "surface_request erode");
    require_same_size(deposit.size(), h.size(), "surface_request deposit");
    require_step(dx, dS);
    const std::size_t n = h.size();
    for (std::size_t c = 0; c < n; ++c) erode[c] = deposit[c] = 0.0;
    switch (law.kind) {
        case SurfaceLawKind::none: break;
        case SurfaceLawKind::elevation: {
            // dh/dS = −k h solved exactly over dS: never past the surface, exact decay.
            const double lost = -std::expm1(-law.k * dS);
            for (std::size_t c = 0; c < n; ++c)
                if (h[c] > 0.0) erode[c] = h[c] * lost * dx;
            break;
        }
        case SurfaceLawKind::slope: slope_request(law.K, h, dx, dS, erode); break;
        case SurfaceLawKind::uniform:
            for (std::size_t c = 0; c < n; ++c)
                if (h[c] > 0.0) erode[c] = clipped_erosion(law.e_dot, h[c], dx, dS);
            break;
        case SurfaceLawKind::cap:
            for (std::size_t c = 0; c < n; ++c) erode[c] = std::max(h[c] - law.H_c, 0.0) * dx;
            break;
        case SurfaceLawKind::diffusion: {
            if (n == 0) break;
            diffuse(law, h, dx, dS, ws);
            for (std::size_t c = 0; c < n; ++c) {
                const double change = (ws.h_new[c] - h[c]) * dx;
                if (change < 0.0) erode[c] = -change;
                else deposit[c] = change;
            }
            break;
        }
    }
    SurfaceTotals t;
    for (std::size_t c = 0; c < n; ++c) {
        t.eroded += erode[c];
        t.deposited += deposit[c];
    }
    return t;
}

double sedimentation_request(const SedimentRule& rule, std::span<const double> h, double dx, double dS,
                             std::span<double> deposit) {
    require_same_size(deposit.size(), h.size(), "sedimentation_request deposit");
    require_step(dx, dS);
    double total = 0.0;
    for (std::size_t c = 0; c < h.size(); ++c) {
        double fill = std::max(rule.base_level - h[c], 0.0);
        if (!rule.at_once) fill = std::min(fill, rule.rate * dS);
        deposit[c] = fill * dx;
        total += deposit[c];
    }
    return total;
}

void apply_areas(std::span<double> h, std::span<const double> erode, std::span<const double> deposit,
                 double dx) {
    require_same_size(erode.size(), h.size(), "apply_areas erode");
    require_same_size(deposit.size(), h.size(), "apply_areas deposit");
    for (std::size_t c = 0; c < h.size(); ++c) h[c] += (deposit[c] - erode[c]) / dx;
}

void take_whole_particles(std::span<double> remainder, std::span<const double> request,
                          std::span<const std::size_t> column_begin, std::span<WholeCandidate> candidates,
                          WholeTake& taken) {
    const std::size_t n = remainder.size();
    require_same_size(request.size(), n, "take_whole_particles request");
    if (column_begin.size() != n + 1 || column_begin[0] != 0 || column_begin[n] != candidates.size())
        throw std::invalid_argument("take_whole_particles: column_begin must run from 0 to the candidate count");
    for (std::size_t c = 0; c < n; ++c) {
        if (column_begin[c + 1] < column_begin[c])
            throw std::invalid_argument("take_whole_particles: column_begin decreases");
        if (!std::isfinite(request[c]) || request[c] < 0.0)
            throw std::invalid_argument("take_whole_particles: requests must be finite and >= 0");
    }
    for (const WholeCandidate& w : candidates)
        if (!std::isfinite(w.area) || w.area <= 0.0 || !std::isfinite(w.height))
            throw std::invalid_argument("take_whole_particles: candidate areas must be finite and > 0, heights finite");

    taken.ids.clear();
    taken.column_begin.clear();
    taken.area = 0.0;
    taken.starved = 0;
    for (std::size_t c = 0; c < n; ++c) {
        taken.column_begin.push_back(taken.ids.size());
        const auto first = candidates.begin() + static_cast<std::ptrdiff_t>(column_begin[c]);
        const auto last = candidates.begin() + static_cast<std::ptrdiff_t>(column_begin[c + 1]);
        std::sort(first, last, [](const WholeCandidate& a, const WholeCandidate& b) {
            return a.height > b.height || (a.height == b.height && a.id < b.id);
        });
        double& r = remainder[c];
        r += request[c];
        auto next = first;
        while (next != last && whole_particle_due(r, next->area)) {
            taken.ids.push_back(next->id);
            taken.area += next->area;
            r -= next->area;
            ++next;
        }
        if (next == last && (first == last ? r > 0.0 : whole_particle_due(r, (last - 1)->area)))
            ++taken.starved;
    }
    taken.column_begin.push_back(taken.ids.size());
}

}  // namespace orodem
