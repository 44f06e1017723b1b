#pragma once
// `pft bench --probe-out DIR` (kind tbd_ir): what tests/tools/ir_probe needs to run the library
// calls of the IR pipeline's flight build on any target (docs/results/ir_clutter.md, "Branch
// ircost31"): the frames (frames.u16, little-endian u16, the simulated sequence), the library
// configurations and the settings between the calls (probe.cfg, key value lines,
// tests/tools/ir_probe_fields.h) and what the host pipeline computed per frame (expect.txt, the
// lines `ir_probe -c` prints: the stage's flags and shift, a checksum of the clutter map's
// output and the reported tracks' fields, all bits).

#include <cstdio>
#include <string>

#include "ir_pipeline.hpp"

namespace pft::host::tbd_ir {

/** Writes probe.cfg for the pipeline pl (throws InputError for a setup ir_probe cannot run). */
void write_probe_config(const std::string &path, const IrPipeline &pl);

/** The line ir_probe -c prints for frame seq, from the pipeline after its step and the step's
 *  output (ends with a newline). */
std::string probe_expect_line(uint32_t seq, const IrPipeline &pl, const PipelineOut &po);

}  // namespace pft::host::tbd_ir
