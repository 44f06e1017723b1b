// Reading a recorded sequence for `pft run` / `pft demo --sequence`:
//  - a directory written by `pft sim` (sequence.json sidecar: PGM 16-bit, raw float32 or raw
//    u16 frames, pixel gain/offset, noise sigma, truth file), read through the port's file
//    source (PGM, float32) or the raw reader below (u16);
//  - a printf pattern of PGM files ("dir/f%04u.pgm"), also through the port's file source;
//  - a folder of images (8/16-bit PGM, PNG, TIFF, ...) or a video, through OpenCV: 16-bit
//    images stay 16-bit, float TIFFs stay float, colour becomes grey;
//  - a headerless dump of u16 frames with the geometry given as `--raw WxH[:bits][:le|be]
//    [:skip=BYTES]`.
// Frames are lent as pft_frame_t, valid until the next call to next().
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

extern "C" {
#include "pft/pft_types.h"
}

namespace pft::host {

struct SequenceInfo {
    std::string source;        ///< what was opened, for messages
    std::string kind;          ///< "pft-sim", "pgm-pattern", "video", "image-folder", "raw-u16"
    int width = 0, height = 0; ///< 0 until known (first frame)
    int frames = -1;           ///< -1 when unknown
    double pixel_gain = 1.0;   ///< U8/U16: intensity = gain * raw + offset
    double pixel_offset = 0.0;
    bool has_scaling = false;  ///< gain/offset come from a sidecar (else 1 and 0: unknown units)
    double noise_sigma = NAN;  ///< the sidecar's noise sigma in intensity units (NaN: none)
    int bit_depth = 0;         ///< significant bits when the source declares them (sidecar, --raw
                               ///< with bits, a PGM's maxval below 65535); 0: not declared
    std::string truth_csv;     ///< ground truth next to the sequence ("" if none)
    nlohmann::json sidecar;    ///< sequence.json when present (its "scenario" member included)
};

class SequenceReader {
public:
    virtual ~SequenceReader() = default;
    /** Next frame, or false at the end. InputError on an unrecoverable read error. */
    virtual bool next(pft_frame_t &frame) = 0;
    const SequenceInfo &info() const { return info_; }
    /** Frames skipped because they could not be read (counted, reported). */
    int skipped() const { return skipped_; }

protected:
    SequenceInfo info_;
    int skipped_ = 0;
};

/** Geometry of a headerless u16 dump: `--raw WxH[:bits][:le|be][:skip=BYTES]`. */
struct RawSpec {
    int width = 0, height = 0;
    int bits = 16;             ///< significant bits, 1..16
    bool bits_given = false;   ///< bits was in the spec (else 16, the container, not a declaration)
    bool big_endian = false;
    uint64_t skip = 0;         ///< header bytes before the first frame
};

/** Significant bits of a binary 16-bit PGM from its maxval (16383: 14); 0 when the file is not
 *  a binary PGM or its header cannot be read. */
int pgm_bits(const std::string &path);

/** Parses a --raw spec; InputError "SOURCE: --raw SPEC: field F: what is wrong". */
RawSpec parse_raw_spec(const std::string &spec, const std::string &source);

/** Opens `path` (see above); `raw_spec` non-empty: a headerless u16 dump of that geometry.
 *  InputError with the reason when it cannot. */
std::unique_ptr<SequenceReader> open_sequence(const std::string &path,
                                              const std::string &raw_spec = "");

/** Frame pixels in intensity units (CV_32F): gain * pixel + offset (every format; colour
 *  frames through their grey value). */
cv::Mat frame_to_mat(const pft_frame_t &f, double gain, double offset);

/** A reader whose first frames can be looked at before they are tracked: head(n) reads up to
 *  n frames ahead and returns copies of them (raw pixel values as CV_32F, no gain applied);
 *  next() then lends those frames again, in order, before going on with the source. */
class LookaheadReader : public SequenceReader {
public:
    explicit LookaheadReader(std::unique_ptr<SequenceReader> inner);
    const std::vector<cv::Mat> &head(int n);
    bool next(pft_frame_t &frame) override;

private:
    struct Held {
        cv::Mat pixels;        ///< the frame's own pixels (its format), continuous
        pft_frame_t frame{};
    };
    std::unique_ptr<SequenceReader> inner_;
    std::vector<Held> held_;
    std::vector<cv::Mat> head_;
    std::size_t replay_ = 0;
    bool inner_done_ = false;
    void sync();
};

/** How `pft run` turns pixels into the tracker's intensity units, and the sigma it uses. */
struct PixelScaling {
    double gain = 1.0, offset = 0.0;  ///< intensity = gain * raw + offset
    double noise_sigma = 0.0;         ///< sigma the tracker is told (intensity units)
    std::string how;                  ///< one line for the log: where the numbers come from
};

/** The scaling of a sequence for a tracker that assumes zero-mean noise of sigma `model_sigma`
 *  (the scenario's):
 *  - the sidecar gives gain/offset: those; sigma = the sidecar's noise_sigma when it has one,
 *    else estimated from the head frames (in intensity units);
 *  - no sidecar: background level (median) and sigma estimated from the head frames in
 *    counts; intensity = (raw - background) * model_sigma / sigma, so the noise has the
 *    scenario's sigma and target intensities are read relative to it.
 *  `head` are raw pixel values (LookaheadReader::head). */
PixelScaling decide_scaling(const SequenceInfo &info, const std::vector<cv::Mat> &head,
                            double model_sigma);

}  // namespace pft::host
