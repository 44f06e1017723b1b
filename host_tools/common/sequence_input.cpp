#include "sequence_input.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

extern "C" {
#include "pft/pft_port_file.h"
}

#include "errors.hpp"
#include "json_field.hpp"

namespace fs = std::filesystem;

namespace pft::host {

namespace {

/** PGM pattern or raw concatenated file, through port/file. */
class PortFileReader : public SequenceReader {
public:
    PortFileReader(const std::string &path, pft_file_layout_t layout, pft_file_encoding_t enc,
                   int w, int h, pft_pixfmt_t fmt, uint32_t first_index, SequenceInfo info)
        : path_(path)
    {
        info_ = std::move(info);
        std::size_t bpp = fmt == PFT_PIX_F32 ? 4 : 2;
        std::size_t bytes = (w > 0 && h > 0) ? static_cast<std::size_t>(w) * h * bpp
                                             : static_cast<std::size_t>(8192) * 8192 * 2 / 16;
        if (enc == PFT_FILE_PNM && (w <= 0 || h <= 0))
            bytes = 16u << 20;  // geometry unknown: room for a 2896x2896 16-bit frame
        buf_.resize(bytes / 8 + 1);
        pft_file_config_t c{};
        c.path = path_.c_str();
        c.layout = layout;
        c.encoding = enc;
        c.first_index = first_index;
        c.width = static_cast<uint16_t>(w > 0 ? w : 0);
        c.height = static_cast<uint16_t>(h > 0 ? h : 0);
        c.format = fmt;
        c.frame_period_us = 1000000u;
        c.buffer = buf_.data();
        c.buffer_bytes = buf_.size() * 8;
        c.slots = 1;
        pft_status_t st = pft_file_source_init(&fs_, &c);
        if (st != PFT_OK)
            throw InputError(info_.source + ": cannot open (" + pft_status_str(st) + ")");
        open_ = true;
    }
    ~PortFileReader() override
    {
        if (lent_)
            pft_file_release(&fs_, &cur_);
        if (open_)
            pft_file_source_close(&fs_);
    }
    bool next(pft_frame_t &frame) override
    {
        if (lent_) {
            pft_file_release(&fs_, &cur_);
            lent_ = false;
        }
        for (int attempt = 0; attempt < 1000; ++attempt) {
            if (info_.frames >= 0 && got_ >= info_.frames)
                return false;
            pft_status_t st = pft_file_acquire(&fs_, &cur_, 0);
            if (st == PFT_OK) {
                lent_ = true;
                ++got_;
                if (!info_.width) {
                    info_.width = cur_.width;
                    info_.height = cur_.height;
                }
                frame = cur_;
                return true;
            }
            if (st == PFT_ERR_EOF)
                return false;
            if (st == PFT_ERR_IO || st == PFT_ERR_FORMAT) {
                // a lost frame: count it and go on (a concatenated file ends by itself)
                ++skipped_;
                std::fprintf(stderr, "pft: warning: %s: frame skipped (%s: %s)\n",
                             fs_.name[0] ? fs_.name : info_.source.c_str(), pft_status_str(st),
                             pft_file_error_str(fs_.last_error));
                if (info_.frames >= 0)
                    ++got_;
                continue;
            }
            throw InputError(info_.source + ": read failed (" + pft_status_str(st) + ")");
        }
        throw InputError(info_.source + ": too many unreadable frames");
    }

private:
    std::string path_;
    std::vector<uint64_t> buf_;
    pft_file_source_t fs_{};
    pft_frame_t cur_{};
    bool open_ = false, lent_ = false;
    int got_ = 0;
};

/** Video file or image folder through OpenCV, as 8-bit grey. */
class OpenCvReader : public SequenceReader {
public:
    explicit OpenCvReader(const std::string &path)
    {
        info_.source = path;
        if (fs::is_directory(path)) {
            info_.kind = "image-folder";
            for (const auto &e : fs::directory_iterator(path)) {
                if (!e.is_regular_file())
                    continue;
                std::string ext = e.path().extension().string();
                std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
                if (ext == ".png" || ext == ".pgm" || ext == ".ppm" || ext == ".jpg" ||
                    ext == ".jpeg" || ext == ".bmp" || ext == ".tif" || ext == ".tiff")
                    files_.push_back(e.path().string());
            }
            std::sort(files_.begin(), files_.end());
            if (files_.empty())
                throw InputError(path + ": no images (png, pgm, ppm, jpg, bmp, tif) in this folder");
            info_.frames = static_cast<int>(files_.size());
        } else {
            info_.kind = "video";
            if (!cap_.open(path))
                throw InputError(path + ": OpenCV cannot open this video");
            double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
            info_.frames = n > 0 ? static_cast<int>(n) : -1;
        }
    }
    bool next(pft_frame_t &frame) override
    {
        cv::Mat img;
        if (info_.kind == "video") {
            if (!cap_.read(img) || img.empty())
                return false;
        } else {
            for (;;) {
                if (idx_ >= files_.size())
                    return false;
                img = cv::imread(files_[idx_++], cv::IMREAD_UNCHANGED);
                if (!img.empty())
                    break;
                ++skipped_;
                std::fprintf(stderr, "pft: warning: %s: unreadable image skipped\n",
                             files_[idx_ - 1].c_str());
            }
        }
        if (img.channels() == 3)
            cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
        else if (img.channels() == 4)
            cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
        if (img.depth() != CV_8U && img.depth() != CV_16U)
            img.convertTo(img, CV_8U);
        if (!info_.width) {
            info_.width = img.cols;
            info_.height = img.rows;
        } else if (img.cols != info_.width || img.rows != info_.height) {
            throw InputError(info_.source + ": frame " + std::to_string(seq_ + 1) +
                             " has a different size");
        }
        cur_ = img.isContinuous() ? img : img.clone();
        frame = pft_frame_t{};
        frame.data = cur_.data;
        frame.width = static_cast<uint16_t>(cur_.cols);
        frame.height = static_cast<uint16_t>(cur_.rows);
        frame.stride_bytes = static_cast<uint32_t>(cur_.step[0]);
        frame.format = cur_.depth() == CV_8U ? PFT_PIX_U8 : PFT_PIX_U16;
        frame.bit_depth = cur_.depth() == CV_8U ? 8 : 16;
        frame.seq = ++seq_;
        frame.timestamp_us = static_cast<uint64_t>(seq_) * 40000u;
        return true;
    }

private:
    cv::VideoCapture cap_;
    std::vector<std::string> files_;
    std::size_t idx_ = 0;
    cv::Mat cur_;
    uint32_t seq_ = 0;
};

std::unique_ptr<SequenceReader> open_sidecar(const std::string &dir)
{
    std::string side = (fs::path(dir) / "sequence.json").string();
    json j = load_json_file(side);
    Field f(j, side);
    SequenceInfo info;
    info.source = dir;
    info.kind = "pft-sim";
    info.sidecar = j;
    std::string fmt = f.choice_or("format", "pgm16", {"pgm16", "raw_f32"});
    info.width = static_cast<int>(f.integer_in("width", 0, 1, 65535));
    info.height = static_cast<int>(f.integer_in("height", 0, 1, 65535));
    info.frames = static_cast<int>(f.integer_in("frames", -1, 0, 100000000));
    info.pixel_gain = f.number_or("pixel_gain", 1.0);
    info.pixel_offset = f.number_or("pixel_offset", 0.0);
    if (f.has("truth"))
        info.truth_csv = (fs::path(dir) / f.string("truth")).string();
    uint32_t first = static_cast<uint32_t>(f.integer_in("first_index", 1, 0, 100000000));
    if (fmt == "pgm16") {
        std::string pat = (fs::path(dir) / f.string_or("pattern", "frame_%04u.pgm")).string();
        return std::make_unique<PortFileReader>(pat, PFT_FILE_PER_FRAME, PFT_FILE_PNM, info.width,
                                                info.height, PFT_PIX_U16, first, info);
    }
    if (!info.width || !info.height)
        f.fail("raw_f32 sequences need width and height");
    std::string file = (fs::path(dir) / f.string_or("file", "frames.f32")).string();
    info.pixel_gain = 1.0;
    info.pixel_offset = 0.0;
    return std::make_unique<PortFileReader>(file, PFT_FILE_CONCAT, PFT_FILE_RAW, info.width,
                                            info.height, PFT_PIX_F32, first, info);
}

}  // namespace

std::unique_ptr<SequenceReader> open_sequence(const std::string &path)
{
    std::error_code ec;
    if (path.find('%') != std::string::npos) {
        SequenceInfo info;
        info.source = path;
        info.kind = "pgm-pattern";
        // a pattern inside a pft sim directory: take its pixel scaling and truth
        fs::path side = fs::path(path).parent_path() / "sequence.json";
        if (fs::exists(side, ec)) {
            json j = load_json_file(side.string());
            Field f(j, side.string());
            info.sidecar = j;
            info.pixel_gain = f.number_or("pixel_gain", 1.0);
            info.pixel_offset = f.number_or("pixel_offset", 0.0);
            if (f.has("truth"))
                info.truth_csv = (side.parent_path() / f.string("truth")).string();
        }
        return std::make_unique<PortFileReader>(path, PFT_FILE_PER_FRAME, PFT_FILE_PNM, 0, 0,
                                                PFT_PIX_U16, 1, info);
    }
    if (!fs::exists(path, ec))
        throw InputError(path + ": no such file or directory");
    if (fs::is_directory(path, ec) && fs::exists(fs::path(path) / "sequence.json", ec))
        return open_sidecar(path);
    return std::make_unique<OpenCvReader>(path);
}

cv::Mat frame_to_mat(const pft_frame_t &f, double gain, double offset)
{
    cv::Mat out(f.height, f.width, CV_32F);
    for (int r = 0; r < f.height; ++r) {
        const uint8_t *row = static_cast<const uint8_t *>(f.data) + static_cast<std::size_t>(r) * f.stride_bytes;
        float *o = out.ptr<float>(r);
        for (int c = 0; c < f.width; ++c) {
            double v = 0;
            switch (f.format) {
            case PFT_PIX_U8: v = gain * row[c] + offset; break;
            case PFT_PIX_U16: {
                uint16_t u;
                std::memcpy(&u, row + 2 * c, 2);
                if (f.bit_depth && f.bit_depth < 16)
                    u = static_cast<uint16_t>(u & ((1u << f.bit_depth) - 1u));
                v = gain * u + offset;
                break;
            }
            case PFT_PIX_F32: {
                float x;
                std::memcpy(&x, row + 4 * c, 4);
                v = x;
                break;
            }
            case PFT_PIX_RES16: {  // whitened residual, Q8.8 sigma units
                int16_t q;
                std::memcpy(&q, row + 2 * c, 2);
                v = q == PFT_RES16_MASKED ? offset : gain * (q / 256.0) + offset;
                break;
            }
            case PFT_PIX_RGB888:
            case PFT_PIX_BGR888: {
                const uint8_t *p = row + 3 * c;
                v = gain * (0.299 * p[f.format == PFT_PIX_RGB888 ? 0 : 2] + 0.587 * p[1] +
                            0.114 * p[f.format == PFT_PIX_RGB888 ? 2 : 0]) + offset;
                break;
            }
            }
            o[c] = static_cast<float>(v);
        }
    }
    return out;
}

}  // namespace pft::host
