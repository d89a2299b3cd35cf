// Pictures of the particle state (SPEC §3; paper Figures 9, 12, 13), drawn
// with Cairo. Each disc is a filled circle at its true radius. x is shown in
// units of h0 with the S point at 0; y in units of h0 above the base.
//
// Colourings: "horizons": alternating bands of initial depth, retroside
// material (side = 1) darker; "displacement": a scalar per disc (the
// relative displacement), white → dark red, scaled so that the
// displacement_quantile of the positive values reads full red and larger
// values are clipped to it. Why not the maximum: a few discs rolling down
// a slope between two outputs move much further relative to their
// neighbours than the discs of a shear zone; scaled to them, the paper-size
// pictures came out nearly white. The 0.99 quantile of 33,000 discs lets up to 330
// such outliers through and still leaves the shear zones (thousands of
// discs) in the colour range.
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
    double displacement_quantile = 0.99;  // of the positive scalars: the full-red value
};

/// Nearest-rank quantile q in (0, 1] of the positive entries of v (the value
/// at rank ceil(q n) of the n positive entries in ascending order); 0 when
/// no entry is positive. Independent of the order of v.
double positive_quantile(const std::vector<double>& v, double q);

/// scalar: per slot, used when color_by = "displacement" (may be null otherwise).
void render_particles(const ParticleStore& p, const std::vector<double>* scalar, const ViewOptions& o,
                      const std::string& path);

/// The picture pair of one output, as `orodem run` writes it and `orodem
/// render` writes it again: figures_dir/horizons_<name>.<ext> and, when rel
/// is given (not for the first output, which has no previous one to move
/// from), figures_dir/displacement_<name>.<ext>, labelled with the
/// experiment and S. view gives the frame; its label and colouring are set
/// here. Returns the number of pictures written.
int render_picture_pair(const ParticleStore& p, const std::vector<double>* rel, ViewOptions view,
                        const std::string& experiment, double S, const std::string& figures_dir,
                        const std::string& name, const std::string& ext = "png");

}  // namespace orodem
