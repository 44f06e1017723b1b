#include "tsa_scene.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <random>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/json_field.hpp"

namespace fs = std::filesystem;

namespace pft::host::tsa {

SceneSpec parse_scene(const nlohmann::json &j, const std::string &file)
{
    SceneSpec s;
    Field r(j, file);
    if (!r.has("scene"))
        return s;
    Field f = r.at("scene");
    f.only({"backgrounds", "width", "height", "frames", "world_scale", "target", "camera", "sensor", "blank",
            "seed_base"});
    if (f.has("backgrounds")) {
        Field b = f.at("backgrounds");
        s.backgrounds.clear();
        for (std::size_t i = 0; i < b.size(); ++i)
            s.backgrounds.push_back(b.at(i).as_string());
        if (s.backgrounds.empty())
            b.fail("expected at least one background");
    }
    s.width = (int)f.integer_in("width", s.width, 64, 4096);
    s.height = (int)f.integer_in("height", s.height, 64, 4096);
    s.frames = (int)f.integer_in("frames", s.frames, 2, 100000);
    s.world_scale = f.number_in("world_scale", s.world_scale, 1.0, 8.0);
    s.seed_base = (uint64_t)f.integer_in("seed_base", (int64_t)s.seed_base, 0, INT64_MAX);
    if (f.has("target")) {
        Field t = f.at("target");
        t.only({"width", "height", "speed", "heading_deg", "accel_frame", "accel_frames", "accel"});
        s.target_w = t.number_in("width", s.target_w, 4, 250);
        s.target_h = t.number_in("height", s.target_h, 4, 250);
        s.speed = t.number_in("speed", s.speed, 0, 100);
        s.heading_deg = t.number_in("heading_deg", s.heading_deg, -360, 360);
        s.accel_frame = (int)t.integer_in("accel_frame", s.accel_frame, -1, 100000);
        s.accel_frames = (int)t.integer_in("accel_frames", s.accel_frames, 0, 100000);
        s.accel = t.number_in("accel", s.accel, -50, 50);
    }
    if (f.has("camera")) {
        Field c = f.at("camera");
        c.only({"profile", "swing_speed", "reversals", "swing_accel", "swing_amplitude", "swing_y", "jitter", "zoom",
                "rotation_deg"});
        s.profile = c.choice_or("profile", s.profile, {"legs", "sine"});
        s.swing_speed = c.number_in("swing_speed", s.swing_speed, 0, 200);
        s.reversals = (int)c.integer_in("reversals", s.reversals, 0, 1000);
        s.swing_accel = c.number_in("swing_accel", s.swing_accel, 0.01, 200);
        s.swing_amplitude = c.number_in("swing_amplitude", s.swing_amplitude, 1, 4096);
        s.rotation_deg = c.number_in("rotation_deg", s.rotation_deg, 0, 45);
        s.swing_y = c.number_in("swing_y", s.swing_y, 0, 2);
        s.jitter = c.number_in("jitter", s.jitter, 0, 50);
        s.zoom = c.number_in("zoom", s.zoom, 0, 0.5);
    }
    if (f.has("sensor")) {
        Field n = f.at("sensor");
        n.only({"noise_sigma", "blur_sigma", "motion_blur", "gain_flicker"});
        s.noise_sigma = n.number_in("noise_sigma", s.noise_sigma, 0, 100);
        s.blur_sigma = n.number_in("blur_sigma", s.blur_sigma, 0, 10);
        s.motion_blur = n.number_in("motion_blur", s.motion_blur, 0, 4);
        s.gain_flicker = n.number_in("gain_flicker", s.gain_flicker, 0, 0.5);
    }
    if (f.has("blank")) {
        Field b = f.at("blank");
        b.only({"frame", "frames"});
        s.blank_frame = (int)b.integer_in("frame", s.blank_frame, -1, 100000);
        s.blank_frames = (int)b.integer_in("frames", s.blank_frames, 0, 100000);
    }
    return s;
}

nlohmann::json scene_to_json(const SceneSpec &s)
{
    return {{"backgrounds", s.backgrounds}, {"width", s.width}, {"height", s.height}, {"frames", s.frames},
            {"world_scale", s.world_scale}, {"seed_base", s.seed_base},
            {"target", {{"width", s.target_w}, {"height", s.target_h}, {"speed", s.speed},
                        {"heading_deg", s.heading_deg}, {"accel_frame", s.accel_frame},
                        {"accel_frames", s.accel_frames}, {"accel", s.accel}}},
            {"camera", {{"profile", s.profile}, {"swing_speed", s.swing_speed}, {"reversals", s.reversals},
                        {"swing_accel", s.swing_accel}, {"swing_amplitude", s.swing_amplitude}, {"swing_y", s.swing_y},
                        {"jitter", s.jitter}, {"zoom", s.zoom}, {"rotation_deg", s.rotation_deg}}},
            {"sensor", {{"noise_sigma", s.noise_sigma}, {"blur_sigma", s.blur_sigma}, {"motion_blur", s.motion_blur},
                        {"gain_flicker", s.gain_flicker}}},
            {"blank", {{"frame", s.blank_frame}, {"frames", s.blank_frames}}}};
}

std::string find_data_file(const std::string &name)
{
    static std::mutex mu;
    static std::map<std::string, std::string> cache;
    std::lock_guard<std::mutex> lock(mu);
    if (auto it = cache.find(name); it != cache.end())
        return it->second;
    std::vector<std::string> dirs;
    if (const char *d = std::getenv("PFT_DATA_DIR"))
        dirs.push_back(d);
    dirs.push_back("/usr/share/doc/opencv-doc/examples/data");
    dirs.push_back("/usr/share/opencv4/samples/data");
    dirs.push_back("/usr/share/doc/opencv-doc/examples");
    std::string tried;
    auto found = [&](const std::string &p) {
        cache[name] = p;
        return p;
    };
    if (fs::exists(name) && fs::is_regular_file(name))
        return found(name);
    for (const auto &d : dirs) {
        fs::path p = fs::path(d) / name, gz = fs::path(d) / (name + ".gz");
        tried += (tried.empty() ? "" : ", ") + p.string() + "[.gz]";
        if (fs::exists(p))
            return found(p.string());
        if (fs::exists(gz)) {
            fs::path out = fs::temp_directory_path() / "pft_tsa_data";
            fs::create_directories(out);
            out /= name;
            if (!fs::exists(out)) {
                std::string tmp = out.string() + ".part";
                std::string cmd = "gzip -dc '" + gz.string() + "' > '" + tmp + "'";
                if (std::system(cmd.c_str()) != 0)
                    throw InputError("cannot decompress " + gz.string());
                fs::rename(tmp, out);
            }
            return found(out.string());
        }
    }
    throw InputError(name + ": not found (install opencv-doc, or set PFT_DATA_DIR); tried " + tried);
}

namespace {

const cv::Mat &background(const std::string &name, double scale)
{
    static std::mutex mu;
    static std::map<std::string, cv::Mat> cache;
    std::lock_guard<std::mutex> lock(mu);
    std::string key = name + "@" + std::to_string(scale);
    auto it = cache.find(key);
    if (it != cache.end())
        return it->second;
    std::string path = find_data_file(name);
    cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
    if (img.empty())
        throw InputError(path + ": cannot read image");
    cv::Mat big;
    cv::resize(img, big, cv::Size(), scale, scale, cv::INTER_CUBIC);
    return cache[key] = big;
}

/* Blurs img along the segment d (image px): a line kernel of length |d|, sampled every 1/8 px
 * and splatted bilinearly. Lengths below 1 px leave the image as it is. */
void motion_blur(cv::Mat &img, cv::Point2d d)
{
    const double len = std::hypot(d.x, d.y);
    if (len < 1.0)
        return;
    const int r = (int)std::ceil(len / 2.0) + 1;
    cv::Mat k = cv::Mat::zeros(2 * r + 1, 2 * r + 1, CV_32F);
    const int steps = (int)std::ceil(len * 8.0);
    for (int i = 0; i <= steps; ++i) {
        const double t = (double)i / steps - 0.5;
        const double x = r + t * d.x, y = r + t * d.y;
        const int x0 = (int)std::floor(x), y0 = (int)std::floor(y);
        const double fx = x - x0, fy = y - y0;
        k.at<float>(y0, x0) += (float)((1 - fx) * (1 - fy));
        k.at<float>(y0, x0 + 1) += (float)(fx * (1 - fy));
        k.at<float>(y0 + 1, x0) += (float)((1 - fx) * fy);
        k.at<float>(y0 + 1, x0 + 1) += (float)(fx * fy);
    }
    k /= cv::sum(k)[0];
    cv::filter2D(img, img, -1, k, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
}

}  // namespace

void render_sequence(const SceneSpec &s, uint64_t seed, std::vector<cv::Mat> &frames,
                     std::vector<TruthRow> &truth, int max_frames)
{
    const cv::Mat &world = background(s.backgrounds[seed % s.backgrounds.size()], s.world_scale);
    std::mt19937_64 gen(seed * 0x9E3779B97F4A7C15ull + 12345u);
    std::normal_distribution<double> nd(0.0, 1.0);
    std::uniform_real_distribution<double> ud(0.0, 1.0);
    cv::RNG cvrng(seed * 2654435761u + 7u);
    const int n = max_frames > 0 ? std::min(max_frames, s.frames) : s.frames;
    frames.clear();
    truth.clear();
    frames.reserve(n);
    truth.reserve(n);

    // vehicle look (seeded)
    // vehicle colours (BGR): red, white, blue, yellow, orange
    static const cv::Scalar palette[] = {{40, 40, 200}, {235, 235, 235}, {190, 90, 30}, {30, 210, 235}, {20, 120, 240}};
    const cv::Scalar body = palette[gen() % 5];
    const cv::Scalar roof = body * 0.75 + cv::Scalar(20, 20, 20);
    const double heading = (s.heading_deg + (ud(gen) - 0.5) * 20.0) * CV_PI / 180.0;
    const cv::Point2d dir_t(std::cos(heading), std::sin(heading)), side(-dir_t.y, dir_t.x);

    // initial geometry: camera at the world centre, swing range centred on it
    cv::Point2d cam(world.cols / 2.0, world.rows / 2.0);
    const int segs = s.reversals + 1;
    const double seg_len = (double)s.frames / segs;
    // the first segment starts at rest and runs half a swing: start the camera half a swing to the left
    cam.x -= 0.5 * s.swing_speed * seg_len * 0.5;
    cv::Point2d tgt = cam + cv::Point2d((ud(gen) - 0.5) * 40.0, (ud(gen) - 0.5) * 40.0);
    if (s.accel_frame >= 0 && s.swing_speed == 0.0) {
        // the acceleration scenario: start on the side the vehicle comes from
        const double ahead = s.speed * s.accel_frame + 0.5 * s.accel * s.accel_frames * s.accel_frames +
                             s.accel * s.accel_frames * std::max(0, s.frames - s.accel_frame - s.accel_frames);
        tgt = cam - dir_t * std::min(ahead * 0.5, 0.4 * std::min(s.width, s.height));
    }
    double v = 0.0, speed = s.speed;
    // "sine" swing: X is the camera's x displacement (image px); the target starts at the swing's
    // turning point, swing_amplitude right of its initial position, and the swing starts gently
    const bool sine = s.profile == "sine";
    const double A = s.swing_amplitude;
    double X = -A;
    int dir = 1, next_rev = 0;
    if (sine)
        cam.x -= A;  // the target appears about swing_amplitude right of the image centre
    // extra effects draw from their own generator, so sequences without them are unchanged
    std::mt19937_64 fx_gen(seed * 0xD1B54A32D192ED03ull + 99u);
    std::normal_distribution<double> fx_nd(0.0, 1.0);
    // "sine": reversal i is due at (i + 1/2 + u_i / 2) frames / reversals, u_i uniform in
    // [-1/2, 1/2] per run, and is taken at the first frame from then on where the swing is fast
    std::vector<int> rev_due;
    if (sine) {
        std::uniform_real_distribution<double> fx_ud(-0.5, 0.5);
        for (int i = 0; i < s.reversals; ++i)
            rev_due.push_back((int)((i + 0.5 + 0.5 * fx_ud(fx_gen)) * s.frames / s.reversals));
    }
    for (int k = 0; k < n; ++k) {
        double vt;
        double gain = 1.0, blur_px = 0.0;
        bool rev_taken = false;
        if (sine) {
            const double u = std::clamp(X / A, -1.0, 1.0);
            const double sp = s.swing_speed * std::max(std::sqrt(1.0 - u * u), 0.1);
            if (dir > 0 && X >= A)
                dir = -1;
            else if (dir < 0 && X <= -A)
                dir = 1;
            // sudden reversal: taken at the first fast frame once due
            if (next_rev < s.reversals && k >= rev_due[(std::size_t)next_rev] &&
                std::abs(v) >= 0.7 * s.swing_speed && v * dir > 0) {
                dir = -dir;
                ++next_rev;
                rev_taken = true;
            }
            vt = dir * sp;
        } else {
            // camera swing: the target speed flips sign at each of the `reversals` instants
            const int seg = std::min(segs - 1, (int)(k / seg_len));
            vt = (seg % 2 == 0 ? 1.0 : -1.0) * s.swing_speed;
        }
        v += std::clamp(vt - v, -s.swing_accel, s.swing_accel);
        X += v;
        const double z = 1.0 + s.zoom * std::sin(2.0 * CV_PI * k / s.frames);
        const cv::Point2d cam_prev = cam;
        cam.x += v / z + s.jitter * nd(gen);
        cam.y += s.swing_y * v / z + s.jitter * nd(gen);
        // target motion on the ground
        if (s.accel_frame >= 0 && k >= s.accel_frame && k < s.accel_frame + s.accel_frames)
            speed += s.accel;
        if (k > 0)
            tgt += dir_t * speed;
        // view transform: image = z R(theta) (world - cam) + centre
        const double th = s.rotation_deg * CV_PI / 180.0 * std::sin(4.0 * CV_PI * k / s.frames);
        const double zc = z * std::cos(th), zs = z * std::sin(th);
        const cv::Point2d c0(s.width / 2.0, s.height / 2.0);
        cv::Mat A2 = (cv::Mat_<double>(2, 3) << zc, -zs, c0.x - (zc * cam.x - zs * cam.y), zs, zc,
                      c0.y - (zs * cam.x + zc * cam.y));
        cv::Mat img;
        cv::warpAffine(world, img, A2, cv::Size(s.width, s.height), cv::INTER_LINEAR, cv::BORDER_REFLECT);
        auto to_img = [&](cv::Point2d w) {
            const cv::Point2d d = w - cam;
            return cv::Point2d(zc * d.x - zs * d.y, zs * d.x + zc * d.y) + c0;
        };
        // vehicle: body, roof, windows, stripes (drawn in image coordinates, anti-aliased)
        const double L = s.target_h / 2.0, Wd = s.target_w / 2.0;
        auto quad = [&](double a0, double a1, double b0, double b1) {
            std::vector<cv::Point> p;
            const cv::Point2d ws[4] = {tgt + dir_t * a0 + side * b0, tgt + dir_t * a1 + side * b0,
                                       tgt + dir_t * a1 + side * b1, tgt + dir_t * a0 + side * b1};
            for (const auto &w : ws) {
                cv::Point2d q = to_img(w) * 16.0;
                p.emplace_back((int)std::lround(q.x), (int)std::lround(q.y));
            }
            return p;
        };
        auto fill = [&](const std::vector<cv::Point> &p, const cv::Scalar &col) {
            cv::fillConvexPoly(img, p, col, cv::LINE_AA, 4);
        };
        fill(quad(-L, L, -Wd, Wd), body);
        fill(quad(-0.35 * L, 0.3 * L, -0.8 * Wd, 0.8 * Wd), roof);
        fill(quad(0.3 * L, 0.55 * L, -0.75 * Wd, 0.75 * Wd), cv::Scalar(35, 30, 25));   // windscreen
        fill(quad(-0.6 * L, -0.4 * L, -0.7 * Wd, 0.7 * Wd), cv::Scalar(45, 40, 35));   // rear window
        fill(quad(-L, L, -0.12 * Wd, 0.12 * Wd), body * 0.5 + cv::Scalar(100, 100, 100)); // stripe
        if (s.motion_blur > 0) {
            // the ground's apparent displacement over the frame: the camera's, negated and rotated
            const cv::Point2d d = cam - cam_prev;
            blur_px = std::hypot(d.x, d.y) * z * s.motion_blur;
            motion_blur(img, cv::Point2d(-(zc * d.x - zs * d.y), -(zs * d.x + zc * d.y)) * s.motion_blur);
        }
        if (s.blur_sigma > 0)
            cv::GaussianBlur(img, img, cv::Size(0, 0), s.blur_sigma);
        if (s.gain_flicker > 0) {
            const double g = std::clamp(1.0 + s.gain_flicker * fx_nd(fx_gen), 0.5, 1.5);
            img.convertTo(img, -1, g, 0.0);
            gain = g;
        }
        if (s.blank(k))
            img.setTo(cv::Scalar(128, 128, 128));
        if (s.noise_sigma > 0) {
            cv::Mat noise(img.size(), CV_16SC3);
            cvrng.fill(noise, cv::RNG::NORMAL, 0, s.noise_sigma);
            cv::Mat tmp;
            img.convertTo(tmp, CV_16SC3);
            tmp += noise;
            tmp.convertTo(img, CV_8UC3);
        }
        // truth
        double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
        for (double a : {-L, L})
            for (double b : {-Wd, Wd}) {
                cv::Point2d q = to_img(tgt + dir_t * a + side * b);
                x0 = std::min(x0, q.x);
                y0 = std::min(y0, q.y);
                x1 = std::max(x1, q.x);
                y1 = std::max(y1, q.y);
            }
        const cv::Point2d c = to_img(tgt);
        truth.push_back({k, c.x, c.y, cv::Rect2d(x0, y0, x1 - x0, y1 - y0), v, gain, blur_px, rev_taken});
        frames.push_back(img);
    }
}

}  // namespace pft::host::tsa
