// Pictures of the particle state (SPEC §3; paper Figures 9, 12, 13), drawn
// with Cairo. Each disc is a filled circle at its true radius. x is shown in
// units of h0 with the S point at 0; y in units of h0 above the base.
//
// Colourings: "horizons": alternating bands of initial depth, retroside
// material (side = 1) darker; "displacement": a scalar per disc in [0, 1]
// (the relative displacement scaled to the interval maximum), white → red.
// The file is written under a temporary name and renamed; format from the
// extension (.png, .svg, .pdf).
#pragma once

#include <string>
#include <vector>

#include "orodem/state/particles.hpp"

namespace orodem {

struct ViewOptions {
    double x_min = 0, x_max = 1;   // visible range [m]
    double y_min = 0, y_max = 1;   // [m]
    double h0 = 1;                 // length unit of the axes [m]
    double x_s = 0;                // S point [m]
    int width_px = 1600;           // picture width; height follows the aspect ratio
    double band = 1;               // horizon band thickness [m]
    std::string color_by = "horizons";  // horizons | displacement
    std::string label;             // legend text, e.g. "exp1  S = 2.50"
};

/// scalar: per slot, used when color_by = "displacement" (may be null otherwise).
void render_particles(const ParticleStore& p, const std::vector<double>* scalar, const ViewOptions& o,
                      const std::string& path);

}  // namespace orodem
