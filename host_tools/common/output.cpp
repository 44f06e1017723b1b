#include "output.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <unistd.h>

#include "errors.hpp"

namespace fs = std::filesystem;

namespace pft::host {

namespace {
std::atomic<unsigned> g_tmp_counter{0};  // distinct temp names for files written in parallel
}

AtomicPath::AtomicPath(std::string final_path) : final_(std::move(final_path))
{
    fs::path p(final_);
    std::string name = "." + p.stem().string() + ".tmp" + std::to_string(::getpid()) + "_" +
                       std::to_string(g_tmp_counter++) + p.extension().string();
    tmp_ = (p.parent_path() / name).string();
}

AtomicPath::~AtomicPath()
{
    if (!done_) {
        std::error_code ec;
        fs::remove(tmp_, ec);
    }
}

void AtomicPath::commit()
{
    std::error_code ec;
    fs::rename(tmp_, final_, ec);
    if (ec)
        throw InputError(final_ + ": cannot write (" + ec.message() + ")");
    done_ = true;
}

void write_text_atomic(const std::string &path, const std::function<void(std::ostream &)> &fill)
{
    AtomicPath ap(path);
    {
        std::ofstream out(ap.tmp());
        if (!out)
            throw InputError(path + ": cannot create file");
        fill(out);
        out.flush();
        if (!out)
            throw InputError(path + ": write failed");
    }
    ap.commit();
}

void write_json_atomic(const std::string &path, const nlohmann::json &j)
{
    write_text_atomic(path, [&](std::ostream &os) { os << j.dump(2) << "\n"; });
}

void ensure_dir(const std::string &dir)
{
    if (dir.empty())
        return;
    std::error_code ec;
    if (fs::exists(dir, ec)) {
        if (!fs::is_directory(dir, ec))
            throw InputError(dir + ": exists and is not a directory");
        return;
    }
    fs::create_directories(dir, ec);
    if (ec)
        throw InputError(dir + ": cannot create directory (" + ec.message() + ")");
}

std::string join_path(const std::string &dir, const std::string &name)
{
    if (dir.empty())
        return name;
    return (fs::path(dir) / name).string();
}

void CsvWriter::sep()
{
    if (!first_)
        os_ << ',';
    first_ = false;
}

CsvWriter &CsvWriter::field(const std::string &s)
{
    sep();
    if (s.find_first_of(",\"\n") == std::string::npos) {
        os_ << s;
    } else {
        os_ << '"';
        for (char c : s)
            os_ << (c == '"' ? "\"\"" : std::string(1, c));
        os_ << '"';
    }
    return *this;
}

CsvWriter &CsvWriter::field(double v)
{
    sep();
    if (std::isnan(v)) {
        os_ << "nan";
    } else {
        std::ostringstream tmp;
        tmp << std::setprecision(9) << v;
        os_ << tmp.str();
    }
    return *this;
}

CsvWriter &CsvWriter::field(long long v)
{
    sep();
    os_ << v;
    return *this;
}

void CsvWriter::end_row()
{
    os_ << '\n';
    first_ = true;
}

std::string fixed_text(double v, int prec, const char *missing)
{
    if (!std::isfinite(v))
        return missing;
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", prec, v);
    return b;
}

}  // namespace pft::host
