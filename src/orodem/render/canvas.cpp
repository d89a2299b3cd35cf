#include "orodem/render/canvas.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

namespace orodem {

namespace {

constexpr const char* kFontFamily = "sans-serif";

/// cairo write function appending to the std::string* closure.
cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

void select_font(cairo_t* cr, double size, bool bold) {
    cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double align_x(HAlign h, double width) { return h == HAlign::left ? 0.0 : h == HAlign::centre ? -0.5 * width : -width; }

/// Offset of the baseline from the anchor, downward in the text's own frame [px].
double baseline_offset(VAlign v, double size) {
    return v == VAlign::top ? kCapHeight * size : v == VAlign::middle ? 0.5 * kCapHeight * size : 0.0;
}

class CairoCanvas final : public Canvas {
public:
    CairoCanvas(const std::string& format, int width, int height) : format_(format) {
        surface_ = format == "pdf" ? cairo_pdf_surface_create_for_stream(append_bytes, &bytes_, width, height)
                                   : cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
        if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
            throw IoError(fmt::format("cannot create a {} x {} picture: {}", width, height,
                                      cairo_status_to_string(cairo_surface_status(surface_))));
        cr_ = cairo_create(surface_);
        cairo_set_source_rgb(cr_, 1, 1, 1);
        cairo_paint(cr_);
    }
    ~CairoCanvas() override {
        if (cr_) cairo_destroy(cr_);
        if (surface_) cairo_surface_destroy(surface_);
    }
    CairoCanvas(const CairoCanvas&) = delete;
    CairoCanvas& operator=(const CairoCanvas&) = delete;

    void disc(double x, double y, double r, Colour c) override {
        set(c);
        cairo_new_sub_path(cr_);
        cairo_arc(cr_, x, y, r, 0, 2 * std::numbers::pi);
        cairo_fill(cr_);
    }
    void ring(double x, double y, double r, Colour c, double width) override {
        set(c);
        cairo_set_line_width(cr_, width);
        cairo_new_sub_path(cr_);
        cairo_arc(cr_, x, y, r, 0, 2 * std::numbers::pi);
        cairo_stroke(cr_);
    }
    void polygon(const std::vector<double>& xy, Colour c, double opacity) override {
        cairo_set_source_rgba(cr_, c.r, c.g, c.b, opacity);
        path(xy);
        cairo_close_path(cr_);
        cairo_fill(cr_);
    }
    void line(double x0, double y0, double x1, double y1, Colour c, double width, bool dashed) override {
        polyline({x0, y0, x1, y1}, c, width, dashed);
    }
    void polyline(const std::vector<double>& xy, Colour c, double width, bool dashed) override {
        set(c);
        cairo_set_line_width(cr_, width);
        cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
        const double dash = 3 * width;
        cairo_set_dash(cr_, &dash, dashed ? 1 : 0, 0);
        path(xy);
        cairo_stroke(cr_);
        cairo_set_dash(cr_, nullptr, 0, 0);
    }
    void fill_rect(double x, double y, double w, double h, Colour c) override {
        set(c);
        cairo_rectangle(cr_, x, y, w, h);
        cairo_fill(cr_);
    }
    void stroke_rect(double x, double y, double w, double h, Colour c, double width) override {
        set(c);
        cairo_set_line_width(cr_, width);
        cairo_rectangle(cr_, x, y, w, h);
        cairo_stroke(cr_);
    }
    void text(const std::string& s, double x, double y, double size, HAlign h, VAlign v, bool bold, bool upright,
              Colour c) override {
        set(c);
        select_font(cr_, size, bold);
        cairo_text_extents_t e;
        cairo_text_extents(cr_, s.c_str(), &e);
        cairo_save(cr_);
        cairo_translate(cr_, x, y);
        if (upright) cairo_rotate(cr_, -std::numbers::pi / 2);
        cairo_move_to(cr_, align_x(h, e.x_advance), baseline_offset(v, size));
        cairo_show_text(cr_, s.c_str());
        cairo_restore(cr_);
    }
    void clip(double x, double y, double w, double h) override {
        cairo_save(cr_);
        cairo_rectangle(cr_, x, y, w, h);
        cairo_clip(cr_);
    }
    void unclip() override { cairo_restore(cr_); }
    std::string finish() override {
        cairo_destroy(cr_);
        cr_ = nullptr;
        cairo_status_t st = CAIRO_STATUS_SUCCESS;
        if (format_ == "png") st = cairo_surface_write_to_png_stream(surface_, append_bytes, &bytes_);
        cairo_surface_finish(surface_);
        if (st == CAIRO_STATUS_SUCCESS) st = cairo_surface_status(surface_);
        cairo_surface_destroy(surface_);
        surface_ = nullptr;
        if (st != CAIRO_STATUS_SUCCESS)
            throw IoError(fmt::format("cannot draw the {} picture: {}", format_, cairo_status_to_string(st)));
        return std::move(bytes_);
    }

private:
    void set(Colour c) { cairo_set_source_rgb(cr_, c.r, c.g, c.b); }
    void path(const std::vector<double>& xy) {
        for (std::size_t k = 0; k + 1 < xy.size(); k += 2)
            k == 0 ? cairo_move_to(cr_, xy[k], xy[k + 1]) : cairo_line_to(cr_, xy[k], xy[k + 1]);
    }
    std::string format_;
    std::string bytes_;  // the PDF or PNG stream
    cairo_surface_t* surface_ = nullptr;
    cairo_t* cr_ = nullptr;
};

std::string hex(Colour c) {
    auto byte = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
    return fmt::format("#{:02x}{:02x}{:02x}", byte(c.r), byte(c.g), byte(c.b));
}

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char ch : s) {
        switch (ch) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += ch;
        }
    }
    return out;
}

class SvgCanvas final : public Canvas {
public:
    SvgCanvas(int width, int height) {
        out_ = fmt::format("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                           "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
                           "viewBox=\"0 0 {0} {1}\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
                           width, height);
    }
    void disc(double x, double y, double r, Colour c) override {
        out_ += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"/>\n", x, y, r, hex(c));
    }
    void ring(double x, double y, double r, Colour c, double width) override {
        out_ += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"none\" stroke=\"{}\" "
                            "stroke-width=\"{:.2f}\"/>\n",
                            x, y, r, hex(c), width);
    }
    void polygon(const std::vector<double>& xy, Colour c, double opacity) override {
        out_ += "<polygon points=\"" + points(xy) + fmt::format("\" fill=\"{}\"", hex(c));
        out_ += opacity < 1.0 ? fmt::format(" fill-opacity=\"{:.3f}\"/>\n", opacity) : std::string("/>\n");
    }
    void line(double x0, double y0, double x1, double y1, Colour c, double width, bool dashed) override {
        out_ += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\"{}/>\n", x0, y0, x1, y1,
                            stroke(c, width, dashed));
    }
    void polyline(const std::vector<double>& xy, Colour c, double width, bool dashed) override {
        out_ += "<polyline points=\"" + points(xy) + "\" fill=\"none\"" + stroke(c, width, dashed) +
                " stroke-linejoin=\"round\"/>\n";
    }
    void fill_rect(double x, double y, double w, double h, Colour c) override {
        out_ += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"/>\n", x,
                            y, w, h, hex(c));
    }
    void stroke_rect(double x, double y, double w, double h, Colour c, double width) override {
        out_ += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\" "
                            "stroke=\"{}\" stroke-width=\"{:.2f}\"/>\n",
                            x, y, w, h, hex(c), width);
    }
    void text(const std::string& s, double x, double y, double size, HAlign h, VAlign v, bool bold, bool upright,
              Colour c) override {
        const char* anchor = h == HAlign::left ? "start" : h == HAlign::centre ? "middle" : "end";
        out_ += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-family=\"{}\" font-size=\"{:.2f}\"{} "
                            "text-anchor=\"{}\" fill=\"{}\"{}>{}</text>\n",
                            x, y + baseline_offset(v, size), kFontFamily, size,
                            bold ? " font-weight=\"bold\"" : "", anchor, hex(c),
                            upright ? fmt::format(" transform=\"rotate(-90 {:.2f} {:.2f})\"", x, y) : std::string(),
                            xml_escape(s));
    }
    void clip(double x, double y, double w, double h) override {
        const int id = ++clips_;
        out_ += fmt::format("<clipPath id=\"clip{}\"><rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" "
                            "height=\"{:.2f}\"/></clipPath>\n<g clip-path=\"url(#clip{})\">\n",
                            id, x, y, w, h, id);
    }
    void unclip() override { out_ += "</g>\n"; }
    std::string finish() override {
        out_ += "</svg>\n";
        return std::move(out_);
    }

private:
    static std::string points(const std::vector<double>& xy) {
        std::string p;
        for (std::size_t k = 0; k + 1 < xy.size(); k += 2) p += fmt::format("{}{:.2f},{:.2f}", k ? " " : "", xy[k], xy[k + 1]);
        return p;
    }
    static std::string stroke(Colour c, double width, bool dashed) {
        return fmt::format(" stroke=\"{}\" stroke-width=\"{:.2f}\"{}", hex(c), width,
                           dashed ? fmt::format(" stroke-dasharray=\"{:.2f}\"", 3 * width) : std::string());
    }
    std::string out_;
    int clips_ = 0;
};

}  // namespace

std::string picture_format(const std::string& path) {
    const auto dot = path.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    if (ext != "png" && ext != "svg" && ext != "pdf")
        throw ConfigError(fmt::format("'{}': the picture format follows the extension, which must be .png, .svg or .pdf",
                                      path));
    return ext;
}

std::unique_ptr<Canvas> make_canvas(const std::string& format, int width, int height) {
    if (format == "svg") return std::make_unique<SvgCanvas>(width, height);
    return std::make_unique<CairoCanvas>(format, width, height);
}

double text_width(const std::string& s, double size, bool bold) {
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t* cr = cairo_create(surface);
    select_font(cr, size, bold);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
    return e.x_advance;
}

}  // namespace orodem
