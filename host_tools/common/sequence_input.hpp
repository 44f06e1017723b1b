// Reading a recorded sequence for `pft run` / `pft demo --sequence`:
//  - a directory written by `pft sim` (sequence.json sidecar: PGM 16-bit or raw float32
//    frames, pixel gain/offset, truth file), read through the port's file source;
//  - a printf pattern of PGM files ("dir/f%04u.pgm"), also through the port's file source;
//  - a video file or a folder of images, through OpenCV (converted to 8-bit grey).
// Frames are lent as pft_frame_t, valid until the next call to next().
#pragma once
#include <memory>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

extern "C" {
#include "pft/pft_types.h"
}

namespace pft::host {

struct SequenceInfo {
    std::string source;        ///< what was opened, for messages
    std::string kind;          ///< "pft-sim", "pgm-pattern", "video", "image-folder"
    int width = 0, height = 0; ///< 0 until known (first frame)
    int frames = -1;           ///< -1 when unknown
    double pixel_gain = 1.0;   ///< U8/U16: intensity = gain * raw + offset
    double pixel_offset = 0.0;
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

/** Opens `path` (see above); InputError with the reason when it cannot. */
std::unique_ptr<SequenceReader> open_sequence(const std::string &path);

/** Frame pixels in intensity units (CV_32F), applying gain/offset to U8/U16 frames and
 *  converting colour frames to grey. */
cv::Mat frame_to_mat(const pft_frame_t &f, double gain, double offset);

}  // namespace pft::host
