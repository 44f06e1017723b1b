// `pft track`: pftrack's TSA-AK (or a baseline) over a video or an image folder from an
// initial box or polygon given on the command line or in a file, with tracker parameters from a
// scenario and/or flags; writes tracks.csv and tracks.json (wall and CPU time per frame), and
// on request overlay.avi and overlay snapshots (no frame is kept in memory). The command line
// is parsed in host_tools/pft/main.cpp into Options::track; the kind registry calls the tsa
// handler's track(), which fills a TrackCli and calls run_track.
#pragma once
#include <string>
#include <vector>

namespace pft::host::tsa {

struct TrackCli {
    std::string sequence, box, polygon, init, out = "pft_track_out", scenario;
    std::string motion;                  ///< empty: the scenario's (default tsa)
    int particles = 0;                   ///< 0: the scenario's (default 100)
    std::vector<std::string> set;        ///< name=value tracker parameters
    std::vector<std::string> compare;    ///< more trackers on the same frames
    int frames = 0, snapshots = 0, max_target = 0;
    std::vector<int> snapshot_at;
    std::string snapshot_format = "png";
    double snapshot_scale = 1.0;
    bool video = false, no_video = false, quiet = false;
};

/** Runs it; returns the exit status (InputError on bad input). */
int run_track(const TrackCli &t);

}  // namespace pft::host::tsa
