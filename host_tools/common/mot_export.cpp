#include "mot_export.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "output.hpp"

namespace pft::host {

namespace {
std::string num(double v)
{
    std::ostringstream os;
    os << std::setprecision(9) << v;
    return os.str();
}
}  // namespace

void write_mot_file(const std::string &path, std::vector<MotRow> rows, double box)
{
    std::stable_sort(rows.begin(), rows.end(), [](const MotRow &a, const MotRow &b) {
        return a.frame != b.frame ? a.frame < b.frame : a.id < b.id;
    });
    write_text_atomic(path, [&](std::ostream &os) {
        for (const MotRow &r : rows)
            os << r.frame << ',' << r.id << ',' << num(r.x + 1.0 - box / 2.0) << ',' << num(r.y + 1.0 - box / 2.0)
               << ',' << num(box) << ',' << num(box) << ',' << num(r.conf) << ',' << num(r.x) << ',' << num(r.y)
               << ",-1\n";
    });
}

void write_mot_layout(const std::string &dir, const std::string &seq, const std::vector<MotRow> &tracks,
                      const std::vector<MotRow> &truth, double box, bool with_truth)
{
    ensure_dir(join_path(dir, "trackers"));
    write_mot_file(join_path(join_path(dir, "trackers"), seq + ".txt"), tracks, box);
    if (with_truth) {
        std::string gt = join_path(join_path(join_path(dir, "gt"), seq), "gt");
        ensure_dir(gt);
        write_mot_file(join_path(gt, "gt.txt"), truth, box);
    }
}

}  // namespace pft::host
