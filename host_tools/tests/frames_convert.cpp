// Test helper (not installed): rewrites the frames of a folder (every .pgm/.png/.tif in name
// order, read with OpenCV at their own bit depth) in another form, so that ctests can feed
// `pft run` the same pixels as PGM, 16-bit PNG, 16-bit TIFF and a headerless u16 dump.
//   pft_frames_convert IN_DIR OUT_DIR pgm|png|tiff          one file per frame in OUT_DIR
//   pft_frames_convert IN_DIR OUT_FILE raw [be] [skip=N] [cut=N]
//        all frames back to back (little-endian unless be), N header bytes first, the last N
//        bytes cut off (a truncated dump)
//   pft_frames_convert IN_FILE OUT_PNG png8                 one 16-bit image as 8-bit (>> 6)
// Any form but png8 also takes shift=S [first=K]: the pixel values of the first K frames (all
// without first=) shifted right by S bits (a sensor's dim first frames, a lower bit depth).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace fs = std::filesystem;

int main(int argc, char **argv)
{
    if (argc < 4) {
        std::fprintf(stderr, "usage: pft_frames_convert IN OUT pgm|png|tiff|raw|png8 [be] [skip=N] [cut=N]\n");
        return 2;
    }
    std::string in = argv[1], out = argv[2], form = argv[3];
    bool be = false;
    long skip = 0, cut = 0, shift = 0, first = -1;
    for (int i = 4; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "be")
            be = true;
        else if (a.rfind("skip=", 0) == 0)
            skip = std::stol(a.substr(5));
        else if (a.rfind("cut=", 0) == 0)
            cut = std::stol(a.substr(4));
        else if (a.rfind("shift=", 0) == 0)
            shift = std::stol(a.substr(6));
        else if (a.rfind("first=", 0) == 0)
            first = std::stol(a.substr(6));
    }
    if (form == "png8") {
        cv::Mat m = cv::imread(in, cv::IMREAD_UNCHANGED), o;
        m.convertTo(o, CV_8U, 1.0 / 64.0);
        return cv::imwrite(out, o) ? 0 : 1;
    }
    std::vector<std::string> files;
    for (const auto &e : fs::directory_iterator(in)) {
        std::string x = e.path().extension().string();
        if (x == ".pgm" || x == ".png" || x == ".tif")
            files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
        std::fprintf(stderr, "%s: no frames\n", in.c_str());
        return 1;
    }
    long index = 0;
    auto shifted = [&](cv::Mat m) {
        if (shift > 0 && (first < 0 || index < first) && m.depth() == CV_16U)
            m.convertTo(m, CV_16U, 1.0 / static_cast<double>(1L << shift), -0.49);  // floor
        ++index;
        return m;
    };
    if (form == "raw") {
        std::vector<char> bytes(static_cast<std::size_t>(skip), static_cast<char>(0xAB));
        for (const std::string &f : files) {
            cv::Mat m = shifted(cv::imread(f, cv::IMREAD_UNCHANGED));
            if (m.depth() != CV_16U || m.channels() != 1) {
                std::fprintf(stderr, "%s: not a 16-bit grey image\n", f.c_str());
                return 1;
            }
            for (int r = 0; r < m.rows; ++r)
                for (int c = 0; c < m.cols; ++c) {
                    uint16_t v = m.at<uint16_t>(r, c);
                    char lo = static_cast<char>(v & 0xFF), hi = static_cast<char>(v >> 8);
                    bytes.push_back(be ? hi : lo);
                    bytes.push_back(be ? lo : hi);
                }
        }
        bytes.resize(bytes.size() - static_cast<std::size_t>(std::min<long>(cut, static_cast<long>(bytes.size()))));
        std::ofstream o(out, std::ios::binary);
        o.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return o ? 0 : 1;
    }
    std::string ext = form == "pgm" ? ".pgm" : form == "png" ? ".png" : form == "tiff" ? ".tif" : "";
    if (ext.empty()) {
        std::fprintf(stderr, "unknown form %s\n", form.c_str());
        return 2;
    }
    fs::create_directories(out);
    for (const std::string &f : files) {
        cv::Mat m = shifted(cv::imread(f, cv::IMREAD_UNCHANGED));
        std::string name = (fs::path(out) / fs::path(f).stem()).string() + ext;
        if (m.empty() || !cv::imwrite(name, m)) {
            std::fprintf(stderr, "%s: cannot convert\n", f.c_str());
            return 1;
        }
    }
    return 0;
}
