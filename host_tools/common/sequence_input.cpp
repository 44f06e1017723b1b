#include "sequence_input.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

extern "C" {
#include "pft/pft_port_file.h"
}

#include "errors.hpp"
#include "json_field.hpp"
#include "noise_estimate.hpp"
#include "plot.hpp"  // natural_less

namespace fs = std::filesystem;

namespace pft::host {

namespace {

/** PGM pattern or raw concatenated file, through port/file. */
class PortFileReader : public SequenceReader {
public:
    PortFileReader(const std::string &path, pft_file_layout_t layout, pft_file_encoding_t enc,
                   int w, int h, pft_pixfmt_t fmt, uint32_t first_index, SequenceInfo info)
        : path_(path), first_index_(first_index)
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
                // frames of the sequence so far, missing ones included (seq is the file index)
                got_ = static_cast<int>(cur_.seq - first_index_ + 1u);
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
                // lost frames: count them and go on (a concatenated file ends by itself); the
                // tracker sees the gap in seq
                uint32_t missing = fs_.stats.missing - missing_;
                missing_ = fs_.stats.missing;
                if (missing > 0u) {
                    skipped_ += static_cast<int>(missing);
                    std::fprintf(stderr, "pft: warning: %s: %u missing file(s), a gap in the sequence\n",
                                 fs_.name[0] ? fs_.name : info_.source.c_str(), missing);
                    got_ += static_cast<int>(missing);
                } else {
                    ++skipped_;
                    std::fprintf(stderr, "pft: warning: %s: frame skipped (%s: %s)\n",
                                 fs_.name[0] ? fs_.name : info_.source.c_str(), pft_status_str(st),
                                 pft_file_error_str(fs_.last_error));
                    ++got_;
                }
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
    uint32_t first_index_ = 0;
    uint32_t missing_ = 0;  // fs_.stats.missing already reported
    int got_ = 0;
};

std::string lower_ext(const fs::path &p)
{
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
    return ext;
}


const uint64_t kFramePeriodUs = 40000;  // image folders and raw dumps: 25 frames/s

/** Video file or image folder through OpenCV: 8-bit stays U8, 16-bit stays U16 (PGM: with
 *  the bit depth of its maxval), float and signed images become F32, colour becomes grey. */
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
                std::string ext = lower_ext(e.path());
                if (ext == ".png" || ext == ".pgm" || ext == ".ppm" || ext == ".jpg" ||
                    ext == ".jpeg" || ext == ".bmp" || ext == ".tif" || ext == ".tiff")
                    files_.push_back(e.path().string());
            }
            std::sort(files_.begin(), files_.end(), natural_less);
            if (files_.empty())
                throw InputError(path + ": no images (png, pgm, ppm, jpg, bmp, tif) in this folder");
            number_files();
            info_.frames = static_cast<int>(seqs_.back());
            std::error_code ec;
            if (fs::exists(fs::path(path) / "truth.csv", ec))
                info_.truth_csv = (fs::path(path) / "truth.csv").string();
        } else {
            std::string ext = lower_ext(path);
            if (ext == ".raw" || ext == ".u16" || ext == ".bin" || ext == ".dat")
                throw InputError(path + ": looks like a headerless dump: give its geometry with "
                                        "--raw WxH[:bits][:le|be][:skip=BYTES]");
            info_.kind = "video";
            if (!cap_.open(path))
                throw InputError(path + ": OpenCV cannot open this video (a headerless dump "
                                        "needs --raw WxH[:bits][:le|be][:skip=BYTES])");
            double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
            info_.frames = n > 0 ? static_cast<int>(n) : -1;
            double fps = cap_.get(cv::CAP_PROP_FPS);
            if (fps > 0.5 && fps < 10000)
                period_us_ = static_cast<uint64_t>(std::llround(1e6 / fps));
        }
    }
    bool next(pft_frame_t &frame) override
    {
        cv::Mat img;
        int bits = 0;
        if (info_.kind == "video") {
            if (!cap_.read(img) || img.empty())
                return false;
        } else {
            for (;;) {
                if (idx_ >= files_.size())
                    return false;
                const std::string &file = files_[idx_];
                uint32_t want = seqs_[idx_++];
                if (want > seq_ + 1u) {
                    // numbers missing from the folder: lost frames, seen by the tracker as a gap
                    skipped_ += static_cast<int>(want - seq_ - 1u);
                    std::fprintf(stderr, "pft: warning: %s: %u frame(s) missing before it, a gap in the sequence\n",
                                 file.c_str(), want - seq_ - 1u);
                }
                seq_ = want - 1u;
                img = cv::imread(file, cv::IMREAD_UNCHANGED);
                if (!img.empty()) {
                    if (lower_ext(file) == ".pgm" && img.depth() == CV_16U) {
                        bits = pgm_bits(file);
                        // the first frame's maxval below 65535 declares the depth (16383: 14
                        // bits); 65535 is only the container's (OpenCV writes it always)
                        if (!info_.width && bits > 0 && bits < 16)
                            info_.bit_depth = bits;
                    }
                    break;
                }
                ++skipped_;
                seq_ = want;  // its sequence number is used up: the tracker sees the gap
                std::fprintf(stderr, "pft: warning: %s: unreadable image skipped\n", file.c_str());
            }
        }
        if (img.channels() == 3)
            cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
        else if (img.channels() == 4)
            cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
        else if (img.channels() != 1)
            throw InputError(source_name() + ": images with " + std::to_string(img.channels()) +
                             " channels are not supported");
        if (img.depth() != CV_8U && img.depth() != CV_16U && img.depth() != CV_32F)
            img.convertTo(img, CV_32F);  // signed or double images: values kept, no squeezing
        if (!info_.width) {
            info_.width = img.cols;
            info_.height = img.rows;
        } else if (img.cols != info_.width || img.rows != info_.height) {
            throw InputError(source_name() + ": frame " + std::to_string(seq_ + 1) + " is " +
                             std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                             ", the first was " + std::to_string(info_.width) + "x" +
                             std::to_string(info_.height));
        }
        cur_ = img.isContinuous() ? img : img.clone();
        frame = pft_frame_t{};
        frame.data = cur_.data;
        frame.width = static_cast<uint16_t>(cur_.cols);
        frame.height = static_cast<uint16_t>(cur_.rows);
        frame.stride_bytes = static_cast<uint32_t>(cur_.step[0]);
        switch (cur_.depth()) {
        case CV_8U: frame.format = PFT_PIX_U8; frame.bit_depth = 8; break;
        case CV_16U: frame.format = PFT_PIX_U16; frame.bit_depth = static_cast<uint8_t>(bits ? bits : 16); break;
        default: frame.format = PFT_PIX_F32; frame.bit_depth = 0; break;
        }
        frame.seq = ++seq_;
        frame.timestamp_us = static_cast<uint64_t>(seq_ - 1) * period_us_;
        return true;
    }

private:
    /** Sequence numbers of the folder's files: from the last number in each name (f0007.png:
     *  7) counted from the first file's, when every name has one, they rise by at most
     *  PFT_FILE_MAX_GAP + 1 and no more numbers are missing than present (then the missing
     *  numbers are lost frames, a gap in seq); else 1, 2, 3... in name order. */
    void number_files()
    {
        std::vector<uint64_t> num;
        for (const auto &f : files_) {
            std::string stem = fs::path(f).stem().string();
            std::size_t e = stem.find_last_of("0123456789");
            if (e == std::string::npos)
                break;
            std::size_t b = e;
            while (b > 0 && std::isdigit(static_cast<unsigned char>(stem[b - 1])))
                --b;
            if (e - b + 1 > 9)
                break;
            num.push_back(std::stoull(stem.substr(b, e - b + 1)));
        }
        bool numbered = num.size() == files_.size();
        for (std::size_t i = 1; numbered && i < num.size(); ++i)
            numbered = num[i] > num[i - 1] && num[i] - num[i - 1] <= PFT_FILE_MAX_GAP + 1u;
        // a sequence with holes, not a set of stills that happen to be numbered: at most
        // PFT_FILE_MAX_GAP numbers missing in a row and no more missing than present
        if (numbered && num.back() - num.front() + 1u > 2u * num.size())
            numbered = false;
        seqs_.resize(files_.size());
        for (std::size_t i = 0; i < files_.size(); ++i)
            seqs_[i] = numbered ? static_cast<uint32_t>(num[i] - num[0] + 1u) : static_cast<uint32_t>(i + 1);
    }

    cv::VideoCapture cap_;
    std::vector<std::string> files_;
    std::vector<uint32_t> seqs_;
    std::size_t idx_ = 0;
    cv::Mat cur_;
    uint32_t seq_ = 0;
    uint64_t period_us_ = kFramePeriodUs;
    std::string source_name() const
    {
        return info_.kind == "video" || idx_ == 0 ? info_.source : files_[idx_ - 1];
    }
};

/** Headerless u16 frames back to back, geometry from a RawSpec. The file size is checked when
 *  it is opened: a dump that does not hold a whole number of frames is refused. */
class RawU16Reader : public SequenceReader {
public:
    RawU16Reader(const std::string &path, const RawSpec &spec, SequenceInfo info, const std::string &what)
        : spec_(spec)
    {
        info_ = std::move(info);
        info_.source = path;
        info_.kind = "raw-u16";
        info_.width = spec.width;
        info_.height = spec.height;
        // a sidecar's bit depth or --raw's bits declare the depth; a spec without bits does not
        if (!info_.bit_depth && spec.bits_given)
            info_.bit_depth = spec.bits;
        std::error_code ec;
        if (fs::is_directory(path, ec))
            throw InputError(path + ": " + what + " names a folder; it needs one file of frames");
        uintmax_t size = fs::file_size(path, ec);
        if (ec)
            throw InputError(path + ": cannot read the size of this file (" + ec.message() + ")");
        frame_bytes_ = static_cast<uint64_t>(spec.width) * spec.height * 2u;
        if (size < spec.skip)
            throw InputError(path + ": " + what + ": field skip: " + std::to_string(spec.skip) +
                             " bytes of header, but the file has only " + std::to_string(size));
        uint64_t body = size - spec.skip;
        if (body == 0)
            throw InputError(path + ": no frames after skip=" + std::to_string(spec.skip) + " bytes");
        if (body % frame_bytes_ != 0)
            throw InputError(path + ": " + what + ": field WxH: " + std::to_string(body) +
                             " bytes after skip=" + std::to_string(spec.skip) + " are not a whole number of " +
                             std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                             " u16 frames (" + std::to_string(frame_bytes_) + " bytes each): " +
                             std::to_string(body / frame_bytes_) + " frames and " +
                             std::to_string(body % frame_bytes_) +
                             " bytes of a truncated one (wrong geometry, skip or a cut file)");
        info_.frames = static_cast<int>(std::min<uint64_t>(body / frame_bytes_, 100000000u));
        in_.open(path, std::ios::binary);
        if (!in_)
            throw InputError(path + ": cannot open");
        in_.seekg(static_cast<std::streamoff>(spec.skip));
        buf_.resize(static_cast<std::size_t>(spec.width) * spec.height);
    }
    bool next(pft_frame_t &frame) override
    {
        if (got_ >= info_.frames)
            return false;
        in_.read(reinterpret_cast<char *>(buf_.data()), static_cast<std::streamsize>(frame_bytes_));
        if (in_.gcount() != static_cast<std::streamsize>(frame_bytes_))
            throw InputError(info_.source + ": frame " + std::to_string(got_ + 1) + ": read failed");
        const uint16_t probe = 1;
        bool host_le = *reinterpret_cast<const uint8_t *>(&probe) == 1;
        if (host_le == spec_.big_endian)
            for (uint16_t &v : buf_)
                v = static_cast<uint16_t>((v >> 8) | (v << 8));
        if (got_ == 0 && spec_.bits < 16) {
            const uint16_t top = static_cast<uint16_t>((1u << spec_.bits) - 1u);
            std::size_t over = 0;
            for (uint16_t v : buf_)
                over += v > top;
            if (over)
                std::fprintf(stderr, "pft: warning: %s: frame 1 has %zu pixels above %d bits "
                             "(max %u): check the bits and the byte order of --raw (the high "
                             "bits are ignored)\n", info_.source.c_str(), over, spec_.bits, top);
        }
        ++got_;
        frame = pft_frame_t{};
        frame.data = buf_.data();
        frame.width = static_cast<uint16_t>(spec_.width);
        frame.height = static_cast<uint16_t>(spec_.height);
        frame.stride_bytes = static_cast<uint32_t>(spec_.width * 2);
        frame.format = PFT_PIX_U16;
        frame.bit_depth = static_cast<uint8_t>(spec_.bits);
        frame.seq = static_cast<uint32_t>(got_);
        frame.timestamp_us = static_cast<uint64_t>(got_ - 1) * kFramePeriodUs;
        return true;
    }

private:
    RawSpec spec_;
    std::ifstream in_;
    std::vector<uint16_t> buf_;
    uint64_t frame_bytes_ = 0;
    int got_ = 0;
};

/** The sidecar fields every format shares: scaling, sigma, truth. */
void sidecar_common(const Field &f, const fs::path &dir, SequenceInfo &info)
{
    info.pixel_gain = f.number_or("pixel_gain", 1.0);
    info.pixel_offset = f.number_or("pixel_offset", 0.0);
    info.has_scaling = f.has("pixel_gain") || f.has("pixel_offset");
    if (f.has("noise_sigma"))
        info.noise_sigma = f.number_req_in("noise_sigma", 1e-12, 1e12);
    info.bit_depth = static_cast<int>(f.integer_in("bit_depth", 0, 0, 16));
    if (f.has("truth"))
        info.truth_csv = (dir / f.string("truth")).string();
}

std::unique_ptr<SequenceReader> open_sidecar(const std::string &dir)
{
    std::string side = (fs::path(dir) / "sequence.json").string();
    json j = load_json_file(side);
    Field f(j, side);
    SequenceInfo info;
    info.source = dir;
    info.kind = "pft-sim";
    info.sidecar = j;
    std::string fmt = f.choice_or("format", "pgm16", {"pgm16", "raw_f32", "raw_u16"});
    info.width = static_cast<int>(f.integer_in("width", 0, 1, 65535));
    info.height = static_cast<int>(f.integer_in("height", 0, 1, 65535));
    check_frame_area(side + ": width x height", static_cast<std::uint64_t>(info.width),
                     static_cast<std::uint64_t>(info.height));
    info.frames = static_cast<int>(f.integer_in("frames", -1, 0, 100000000));
    sidecar_common(f, dir, info);
    uint32_t first = static_cast<uint32_t>(f.integer_in("first_index", 1, 0, 100000000));
    if (fmt == "pgm16") {
        std::string pat = (fs::path(dir) / f.string_or("pattern", "frame_%04u.pgm")).string();
        return std::make_unique<PortFileReader>(pat, PFT_FILE_PER_FRAME, PFT_FILE_PNM, info.width,
                                                info.height, PFT_PIX_U16, first, info);
    }
    if (!info.width || !info.height)
        f.fail(fmt + " sequences need width and height");
    if (fmt == "raw_u16") {
        RawSpec spec;
        spec.width = info.width;
        spec.height = info.height;
        spec.bits = info.bit_depth ? info.bit_depth : 16;
        spec.bits_given = info.bit_depth > 0;
        spec.big_endian = f.choice_or("endian", "le", {"le", "be"}) == "be";
        spec.skip = static_cast<uint64_t>(f.integer_in("skip", 0, 0, INT64_MAX));
        std::string file = (fs::path(dir) / f.string_or("file", "frames.u16")).string();
        auto rd = std::make_unique<RawU16Reader>(file, spec, info, side);
        return rd;
    }
    std::string file = (fs::path(dir) / f.string_or("file", "frames.f32")).string();
    info.pixel_gain = 1.0;
    info.pixel_offset = 0.0;
    return std::make_unique<PortFileReader>(file, PFT_FILE_CONCAT, PFT_FILE_RAW, info.width,
                                            info.height, PFT_PIX_F32, first, info);
}

int spec_int(const std::string &text, const std::string &field, long lo, long hi,
             const std::string &where)
{
    std::size_t used = 0;
    long v = 0;
    try {
        v = std::stol(text, &used, 10);
    } catch (const std::exception &) {
        used = 0;
    }
    if (text.empty() || used != text.size() || !std::isdigit(static_cast<unsigned char>(text[0])))
        throw InputError(where + ": field " + field + ": expected a number, got \"" + text + "\"");
    if (v < lo || v > hi)
        throw InputError(where + ": field " + field + ": " + text + " is outside " +
                         std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(v);
}

}  // namespace

int pgm_bits(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    if (!(in >> magic) || magic != "P5")
        return 0;
    long v[3];
    for (long &x : v) {
        in >> std::ws;
        while (in.peek() == '#') {
            std::string line;
            std::getline(in, line);
            in >> std::ws;
        }
        if (!(in >> x))
            return 0;
    }
    int bits = 1;
    while (bits < 16 && (1L << bits) - 1 < v[2])
        ++bits;
    return bits;
}

RawSpec parse_raw_spec(const std::string &spec, const std::string &source)
{
    const std::string where = source + ": --raw " + spec;
    const std::string syntax = " (syntax: WxH[:bits][:le|be][:skip=BYTES], e.g. 384x288:14:le)";
    std::vector<std::string> parts;
    std::size_t p0 = 0;
    for (;;) {
        std::size_t p = spec.find(':', p0);
        parts.push_back(spec.substr(p0, p == std::string::npos ? std::string::npos : p - p0));
        if (p == std::string::npos)
            break;
        p0 = p + 1;
    }
    RawSpec r;
    std::size_t x = parts[0].find_first_of("xX");
    if (parts[0].empty() || x == std::string::npos)
        throw InputError(where + ": field WxH: expected WIDTHxHEIGHT, got \"" + parts[0] + "\"" + syntax);
    r.width = spec_int(parts[0].substr(0, x), "W", 1, 65535, where);
    r.height = spec_int(parts[0].substr(x + 1), "H", 1, 65535, where);
    check_frame_area(where, static_cast<std::uint64_t>(r.width), static_cast<std::uint64_t>(r.height));
    bool seen_bits = false, seen_endian = false, seen_skip = false;
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const std::string &t = parts[i];
        if (t == "le" || t == "be") {
            if (seen_endian)
                throw InputError(where + ": field le|be: given twice" + syntax);
            seen_endian = true;
            r.big_endian = t == "be";
        } else if (t.rfind("skip=", 0) == 0) {
            if (seen_skip)
                throw InputError(where + ": field skip: given twice" + syntax);
            seen_skip = true;
            std::string v = t.substr(5);
            std::size_t used = 0;
            unsigned long long s = 0;
            try {
                s = std::stoull(v, &used, 10);
            } catch (const std::exception &) {
                used = 0;
            }
            if (v.empty() || used != v.size() || !std::isdigit(static_cast<unsigned char>(v[0])))
                throw InputError(where + ": field skip: expected a byte count, got \"" + v + "\"");
            r.skip = s;
        } else if (!t.empty() && std::isdigit(static_cast<unsigned char>(t[0]))) {
            if (seen_bits)
                throw InputError(where + ": field bits: given twice" + syntax);
            seen_bits = true;
            r.bits = spec_int(t, "bits", 1, 16, where);
            r.bits_given = true;
        } else {
            throw InputError(where + ": field " + std::to_string(i + 1) + " (\"" + t +
                             "\"): expected bits (1..16), le, be or skip=BYTES" + syntax);
        }
    }
    return r;
}

std::unique_ptr<SequenceReader> open_sequence(const std::string &path, const std::string &raw_spec)
{
    std::error_code ec;
    if (!raw_spec.empty()) {
        RawSpec spec = parse_raw_spec(raw_spec, path);
        if (!fs::exists(path, ec))
            throw InputError(path + ": no such file or directory");
        SequenceInfo info;
        fs::path truth = fs::path(path).parent_path() / "truth.csv";
        if (fs::exists(truth, ec))
            info.truth_csv = truth.string();
        return std::make_unique<RawU16Reader>(path, spec, info, "--raw " + raw_spec);
    }
    if (path.find('%') != std::string::npos) {
        SequenceInfo info;
        info.source = path;
        info.kind = "pgm-pattern";
        // a pattern inside a pft sim directory: take its pixel scaling, sigma and truth
        fs::path side = fs::path(path).parent_path() / "sequence.json";
        if (fs::exists(side, ec)) {
            json j = load_json_file(side.string());
            Field f(j, side.string());
            info.sidecar = j;
            sidecar_common(f, side.parent_path(), info);
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
                v = gain * x + offset;
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

// ------------------------------------------------------------------------- lookahead
LookaheadReader::LookaheadReader(std::unique_ptr<SequenceReader> inner) : inner_(std::move(inner))
{
    sync();
}

void LookaheadReader::sync()
{
    info_ = inner_->info();
    skipped_ = inner_->skipped();
}

const std::vector<cv::Mat> &LookaheadReader::head(int n)
{
    while (!inner_done_ && static_cast<int>(held_.size()) < n && replay_ == 0) {
        pft_frame_t f{};
        if (!inner_->next(f)) {
            inner_done_ = true;
            break;
        }
        Held h;
        int type = f.format == PFT_PIX_U8 ? CV_8UC1
                   : f.format == PFT_PIX_U16 ? CV_16UC1
                   : f.format == PFT_PIX_F32 ? CV_32FC1
                                             : CV_8UC3;
        cv::Mat view(f.height, f.width, type, const_cast<void *>(f.data), f.stride_bytes);
        h.pixels = view.clone();
        h.frame = f;
        h.frame.data = h.pixels.data;
        h.frame.stride_bytes = static_cast<uint32_t>(h.pixels.step[0]);
        head_.push_back(frame_to_mat(h.frame, 1.0, 0.0));
        held_.push_back(std::move(h));
    }
    sync();
    return head_;
}

bool LookaheadReader::next(pft_frame_t &frame)
{
    if (replay_ < held_.size()) {
        frame = held_[replay_++].frame;
        return true;
    }
    if (inner_done_)
        return false;
    bool ok = inner_->next(frame);
    sync();
    return ok;
}

// ------------------------------------------------------------------------- scaling
PixelScaling decide_scaling(const SequenceInfo &info, const std::vector<cv::Mat> &head,
                            double model_sigma)
{
    PixelScaling s;
    char b[512];
    if (info.has_scaling || info.kind == "pft-sim") {
        s.gain = info.pixel_gain;
        s.offset = info.pixel_offset;
        if (std::isfinite(info.noise_sigma)) {
            s.noise_sigma = info.noise_sigma;
            std::snprintf(b, sizeof b, "pixel scaling and sigma %.4g from the sidecar", s.noise_sigma);
            s.how = b;
            if (std::fabs(s.noise_sigma - model_sigma) > 1e-3 * model_sigma) {
                std::snprintf(b, sizeof b, " (the scenario says %.4g)", model_sigma);
                s.how += b;
            }
            return s;
        }
        NoiseEstimate e = estimate_noise_spatial(head);
        s.noise_sigma = std::fabs(s.gain) * e.sigma;
        if (e.degenerate || !(s.noise_sigma > 0.0)) {
            s.noise_sigma = model_sigma;
            s.how = "pixel scaling from the sidecar; sigma: the frames are constant, the scenario's used";
            return s;
        }
        std::snprintf(b, sizeof b, "pixel scaling from the sidecar; sigma %.4g estimated (robust %s "
                      "estimate, %d frames, %ld residuals)", s.noise_sigma, e.method.c_str(), e.frames, e.samples);
        s.how = b;
        return s;
    }
    NoiseEstimate e = estimate_noise_spatial(head);
    s.noise_sigma = model_sigma;
    if (e.degenerate) {
        s.gain = 1.0;
        s.offset = -e.background;
        std::snprintf(b, sizeof b, "no sidecar; the first %d frames are constant (%.6g): sigma "
                      "cannot be estimated, the scenario's %.4g is used", e.frames, e.background,
                      model_sigma);
        s.how = b;
        return s;
    }
    s.gain = model_sigma / e.sigma;
    s.offset = -e.background * s.gain;
    std::snprintf(b, sizeof b, "no sidecar; estimated from the first %d frames: background %.6g, "
                  "noise sigma %.5g (raw units; robust %s estimate: the frame minus its 8-neighbour "
                  "mean, %ld residuals); intensity = (raw - %.6g) * %.6g so that sigma = %.4g, the "
                  "scenario's", e.frames, e.background, e.sigma, e.method.c_str(), e.samples,
                  e.background, s.gain, model_sigma);
    s.how = b;
    return s;
}

}  // namespace pft::host
