// `pft track`: pftrack's TSA-AK (or a baseline) over a video or an image folder from an
// initial box or polygon given on the command line or in a file; writes tracks.csv,
// tracks.json, overlay.avi and a few overlay PNG snapshots.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace pft::host::tsa {

struct TrackCli {
    std::string sequence, box, polygon, init, out = "pft_track_out", motion = "tsa";
    int particles = 100, frames = 0, snapshots = 4, max_target = 0;
    bool no_video = false, quiet = false;
};

/** Adds the `track` subcommand to app, filling t. */
CLI::App *add_track_command(CLI::App &app, TrackCli &t);
/** Runs it; returns the exit status (InputError on bad input). */
int run_track(const TrackCli &t);

}  // namespace pft::host::tsa
