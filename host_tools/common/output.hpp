// Safe output: everything is written under a temporary name in the destination directory and
// renamed over the final name only when complete, so a failed run never leaves a truncated file
// in place of a good one.
#pragma once
#include <functional>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

namespace pft::host {

/** A temporary sibling path of `final_path` that keeps its extension (OpenCV picks encoders by
 *  extension). commit() renames it into place; the destructor removes it if never committed. */
class AtomicPath {
public:
    explicit AtomicPath(std::string final_path);
    ~AtomicPath();
    AtomicPath(const AtomicPath &) = delete;
    AtomicPath &operator=(const AtomicPath &) = delete;

    const std::string &tmp() const { return tmp_; }
    const std::string &final_path() const { return final_; }
    void commit();  ///< InputError if the rename fails

private:
    std::string final_;
    std::string tmp_;
    bool done_ = false;
};

/** Writes a text file atomically through `fill`; InputError if it cannot be written. */
void write_text_atomic(const std::string &path, const std::function<void(std::ostream &)> &fill);
/** Pretty-printed JSON, atomically. */
void write_json_atomic(const std::string &path, const nlohmann::json &j);
/** Creates a directory (and parents); InputError if it exists as a file or cannot be made. */
void ensure_dir(const std::string &dir);
/** dir + "/" + name, or name when dir is empty. */
std::string join_path(const std::string &dir, const std::string &name);
/** v in fixed notation with prec decimals, or `missing` when v is not finite (tables, CSV). */
std::string fixed_text(double v, int prec, const char *missing);

/** Minimal CSV row writer: numbers with full precision, strings quoted when needed. */
class CsvWriter {
public:
    explicit CsvWriter(std::ostream &os) : os_(os) {}
    CsvWriter &field(const std::string &s);
    CsvWriter &field(const char *s) { return field(std::string(s)); }
    CsvWriter &field(double v);
    CsvWriter &field(long long v);
    CsvWriter &field(int v) { return field(static_cast<long long>(v)); }
    CsvWriter &field(unsigned v) { return field(static_cast<long long>(v)); }
    CsvWriter &field(bool v) { return field(static_cast<long long>(v ? 1 : 0)); }
    void end_row();

private:
    std::ostream &os_;
    bool first_ = true;
    void sep();
};

}  // namespace pft::host
