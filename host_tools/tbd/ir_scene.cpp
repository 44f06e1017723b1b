#include "ir_scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/sequence_input.hpp"
#include "../common/plot.hpp"  // natural_less

namespace fs = std::filesystem;

namespace pft::host::tbd_ir {

namespace {

const double kMinCell = 6.0;  // finest cell of the procedural textures, px

bool is_image(const fs::path &p)
{
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e == ".png" || e == ".pgm" || e == ".tif" || e == ".tiff" || e == ".bmp" || e == ".jpg" ||
           e == ".jpeg";
}

float smoothstep01(float t)
{
    t = std::min(1.0f, std::max(0.0f, t));
    return t * t * (3.0f - 2.0f * t);
}

double quantile(const cv::Mat &m, double q)
{
    std::vector<float> v;
    v.reserve(m.total() / 4 + 1);
    for (int r = 0; r < m.rows; r += 2) {
        const float *p = m.ptr<float>(r);
        for (int c = 0; c < m.cols; c += 2)
            v.push_back(p[c]);
    }
    std::size_t k = static_cast<std::size_t>(std::min(1.0, std::max(0.0, q)) * (v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

}  // namespace

cv::Mat fractal_noise(int w, int h, double scale, double min_cell, cv::RNG &rng)
{
    cv::Mat acc = cv::Mat::zeros(h, w, CV_32F);
    double amp = 1.0;
    for (int o = 0; o < 16; ++o) {
        double cell = scale / std::pow(2.0, o);
        if (cell < min_cell && o > 0)
            break;
        int gw = static_cast<int>(std::ceil(w / cell)) + 4, gh = static_cast<int>(std::ceil(h / cell)) + 4;
        cv::Mat g(gh, gw, CV_32F);
        rng.fill(g, cv::RNG::UNIFORM, -1.0, 1.0);
        cv::Mat up;
        cv::resize(g, up, cv::Size(static_cast<int>(std::lround(gw * cell)), static_cast<int>(std::lround(gh * cell))),
                   0, 0, cv::INTER_CUBIC);
        int off = static_cast<int>(std::lround(cell));
        acc += amp * up(cv::Rect(off, off, w, h));
        amp *= 0.5;
    }
    cv::Scalar mean, sd;
    cv::meanStdDev(acc, mean, sd);
    acc -= mean[0];
    if (sd[0] > 0)
        acc /= sd[0];
    return acc;
}

std::vector<std::string> background_files(const Background &b)
{
    std::vector<std::string> v;
    std::error_code ec;
    if (!fs::is_directory(b.folder, ec))
        throw InputError(b.folder + ": background folder not found (background.folder or --backgrounds)");
    if (!b.files.empty()) {
        for (const std::string &f : b.files) {
            fs::path p = fs::path(b.folder) / f;
            if (!fs::exists(p, ec))
                throw InputError(p.string() + ": no such background image (background.files)");
            v.push_back(p.string());
        }
        return v;
    }
    for (const auto &e : fs::directory_iterator(b.folder))
        if (e.is_regular_file() && is_image(e.path()))
            v.push_back(e.path().string());
    std::sort(v.begin(), v.end(), natural_less);
    if (v.empty())
        throw InputError(b.folder + ": no background images (png, pgm, tif, bmp, jpg) in this folder");
    return v;
}

std::vector<SceneObject> read_yolo_labels(const std::string &path, int width, int height)
{
    std::vector<SceneObject> out;
    std::ifstream in(path);
    if (!in)
        return out;
    std::string line;
    int ln = 0;
    while (std::getline(in, line)) {
        ++ln;
        if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
        std::istringstream ss(line);
        double cls, cx, cy, w, h;
        if (!(ss >> cls >> cx >> cy >> w >> h) || cx < 0 || cx > 1 || cy < 0 || cy > 1 || w < 0 ||
            w > 1 || h < 0 || h > 1)
            throw InputError(path + ":" + std::to_string(ln) +
                             ": expected `class cx cy w h` with fractions in 0..1");
        SceneObject o;
        o.cls = static_cast<int>(cls);
        // fractions cover the image [0, W] of pixel edges; 0-based centres are half a pixel less
        o.x = cx * width - 0.5;
        o.y = cy * height - 0.5;
        o.w = w * width;
        o.h = h * height;
        out.push_back(o);
    }
    return out;
}

double object_amplitude(const cv::Mat &counts, const SceneObject &o)
{
    int hw = std::max(1, static_cast<int>(std::ceil(o.w / 2))), hh = std::max(1, static_cast<int>(std::ceil(o.h / 2)));
    int cx = static_cast<int>(std::lround(o.x)), cy = static_cast<int>(std::lround(o.y));
    cv::Rect img(0, 0, counts.cols, counts.rows);
    cv::Rect box = cv::Rect(cx - hw, cy - hh, 2 * hw + 1, 2 * hh + 1) & img;
    cv::Rect outer = cv::Rect(cx - hw - 4, cy - hh - 4, 2 * hw + 9, 2 * hh + 9) & img;
    if (box.area() == 0)
        return NAN;
    double peak;
    cv::minMaxLoc(counts(box), nullptr, &peak);
    std::vector<float> ring;
    for (int r = outer.y; r < outer.y + outer.height; ++r)
        for (int c = outer.x; c < outer.x + outer.width; ++c)
            if (std::abs(c - cx) > hw + 2 || std::abs(r - cy) > hh + 2)
                ring.push_back(counts.at<float>(r, c));
    if (ring.empty())
        return NAN;
    std::nth_element(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(ring.size() / 2), ring.end());
    return peak - ring[ring.size() / 2];
}

Scene procedural_scene(const IrScenario &s, int W, int H, double y0, int frame_h, uint64_t seed)
{
    const Procedural &P = s.background.proc;
    cv::RNG rng(seed * 0x9E3779B97F4A7C15ull + 0x5DEECE66Dull);
    Scene sc;
    sc.source = "procedural";
    // horizon ridge (scene rows): none -> below the scene
    std::vector<float> ridge(static_cast<std::size_t>(W), static_cast<float>(H + 10));
    if (P.horizon) {
        cv::Mat rn = fractal_noise(W, 1, 48.0, 3.0, rng);
        double base = y0 + *P.horizon * frame_h;
        for (int c = 0; c < W; ++c)
            ridge[static_cast<std::size_t>(c)] = static_cast<float>(base + 0.025 * frame_h * rn.at<float>(0, c));
        // structures: towers and blocks standing on the ridge
        for (int k = 0; k < P.structures; ++k) {
            bool tower = k % 2 == 0;
            int bw = tower ? rng.uniform(2, 6) : rng.uniform(10, 30);
            int bh = tower ? rng.uniform(10, 40) : rng.uniform(5, 12);
            int x0 = rng.uniform(0, std::max(1, W - bw));
            float top = ridge[static_cast<std::size_t>(x0)] - static_cast<float>(bh);
            for (int c = x0; c < x0 + bw && c < W; ++c)
                ridge[static_cast<std::size_t>(c)] = std::min(ridge[static_cast<std::size_t>(c)], top);
        }
    }
    // clouds: fractal field thresholded at the cover quantile, soft edges of cloud_edge_px
    // structure down to cells of kMinCell px: finer random texture would be point-like
    // clutter everywhere (real cloud texture is smoother than that at the sensor's scale)
    cv::Mat n1 = fractal_noise(W, H, P.cloud_scale_px, kMinCell, rng);
    cv::Mat n2 = fractal_noise(W, H, P.cloud_scale_px / 3.0, kMinCell, rng);
    cv::Mat n3 = fractal_noise(W, H, 24.0, kMinCell, rng);
    double t = P.cloud_cover <= 0 ? 1e9 : quantile(n1, 1.0 - P.cloud_cover);
    cv::Mat gx, gy, mag;
    cv::Sobel(n1, gx, CV_32F, 1, 0, 3, 1.0 / 8.0);
    cv::Sobel(n1, gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
    cv::magnitude(gx, gy, mag);
    double gmean = cv::mean(mag)[0];
    double w = std::max(1e-6, P.cloud_edge_px * gmean);
    double fs_ = s.sensor.full_scale();
    double hz_frame = P.horizon ? *P.horizon * frame_h : frame_h;
    sc.counts.create(H, W, CV_32F);
    for (int r = 0; r < H; ++r) {
        const float *a = n1.ptr<float>(r), *b = n2.ptr<float>(r), *g = n3.ptr<float>(r);
        float *o = sc.counts.ptr<float>(r);
        double fr = (r - y0) / hz_frame;  // linear over the whole scene: no kink to drift by
        double sky = P.sky_top + (P.sky_horizon - P.sky_top) * fr;
        for (int c = 0; c < W; ++c) {
            float rid = ridge[static_cast<std::size_t>(c)];
            double v;
            if (r < rid) {
                float m = smoothstep01(static_cast<float>((a[c] - t) / w + 0.5));
                double cl = P.cloud_level * m * std::max(0.0, 1.0 + P.cloud_texture * b[c]);
                v = sky + cl;
            } else {
                double depth = (r - rid) / std::max(1.0, static_cast<double>(H - rid));
                v = P.ground_level + 0.05 * depth + P.ground_texture * g[c];
                if (r < rid + 1.0)  // the ridge row: a one-pixel blend
                    v = 0.5 * (v + sky);
            }
            o[c] = static_cast<float>(std::min(1.0, std::max(0.0, v)) * fs_);
        }
    }
    if (s.optics_blur_px > 0)
        cv::GaussianBlur(sc.counts, sc.counts, cv::Size(0, 0), s.optics_blur_px, s.optics_blur_px,
                         cv::BORDER_REFLECT_101);
    return sc;
}

Scene image_scene(const IrScenario &s, const std::string &file)
{
    cv::Mat img = cv::imread(file, cv::IMREAD_UNCHANGED);
    if (img.empty())
        throw InputError(file + ": cannot read this background image");
    if (img.channels() == 3)
        cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
    else if (img.channels() == 4)
        cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
    Scene sc;
    sc.source = file;
    sc.image_bits = img.depth() == CV_8U ? 8 : img.depth() == CV_16U ? 16 : 0;
    if (!sc.image_bits)
        throw InputError(file + ": background images must be 8- or 16-bit");
    if (sc.image_bits == 16) {
        // a 16-bit PGM declares its bits by a maxval below 65535 (16383: 14 bits); a 16-bit PNG
        // or TIFF does not, and a sensor's 12- or 14-bit frames saved in one would be scaled by
        // 2^(bit_depth - 16), their clutter squeezed 4 or 16 times: unless background.scale
        // says how to read it, such an image is refused when its values leave the top bit free
        std::string ext = fs::path(file).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
        // (a maxval of 65535 is only the container's: OpenCV writes it for every 16-bit PGM)
        const int maxval_bits = ext == ".pgm" ? pgm_bits(file) : 0;
        const int declared = maxval_bits < 16 ? maxval_bits : 0;
        if (declared > 0)
            sc.image_bits = declared;
        else if (s.background.scale <= 0) {
            double mx = 0.0;
            cv::minMaxLoc(img, nullptr, &mx);
            int used = 1;
            while (used < 16 && std::ldexp(1.0, used) - 1.0 < mx)
                ++used;
            if (used < 16)
                throw InputError(file + ": a 16-bit image whose values fit in " + std::to_string(used) +
                                 " bits (largest " + std::to_string(static_cast<long>(mx)) +
                                 "): its own bit depth is not known, so background.scale cannot default to 2^(" +
                                 std::to_string(s.sensor.bit_depth) + " - 16); give background.scale (counts "
                                 "per image unit: 2^(" + std::to_string(s.sensor.bit_depth) +
                                 " - B) for B-bit data, 1 for frames of this sensor's depth)");
        }
    }
    double scale = s.background.scale > 0 ? s.background.scale
                                           : std::pow(2.0, s.sensor.bit_depth - sc.image_bits);
    img.convertTo(sc.counts, CV_32F, scale);
    // smooth_px: the image's own quantisation steps (one 8-bit level is 64 counts, 3.2 temporal
    // sigmas, at 14 bits) and frozen pixel noise would move with the scene as texture that a
    // sensor of this bit depth does not see (docs/results/ir_clutter.md, "Branch irdet")
    if (s.background.smooth_px > 0)
        cv::GaussianBlur(sc.counts, sc.counts, cv::Size(0, 0), s.background.smooth_px, s.background.smooth_px,
                         cv::BORDER_REFLECT_101);
    if (s.optics_blur_px > 0)
        cv::GaussianBlur(sc.counts, sc.counts, cv::Size(0, 0), s.optics_blur_px, s.optics_blur_px,
                         cv::BORDER_REFLECT_101);
    if (s.background.labels) {
        fs::path lab = fs::path(file).replace_extension(".txt");
        sc.objects = read_yolo_labels(lab.string(), img.cols, img.rows);
        for (SceneObject &o : sc.objects) {
            double a = object_amplitude(sc.counts, o);
            o.snr_db = a > 0 ? 20.0 * std::log10(a / s.sensor.noise_sigma) : NAN;
        }
    }
    return sc;
}

}  // namespace pft::host::tbd_ir
