// Reading JSON scenario files with errors that name the bad field ("two_case1.json:
// targets[1].birth_frame: expected an integer, got \"seven\"").
#pragma once
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "errors.hpp"

namespace pft::host {

using json = nlohmann::json;

/** Parses a JSON file; InputError on a missing/unreadable file or a syntax error. */
json load_json_file(const std::string &path);

/** A JSON node together with the file and path it came from, for error messages. */
class Field {
public:
    Field(const json &node, std::string file, std::string path = "");

    const json &node() const { return *node_; }
    const std::string &path() const { return path_; }
    std::string where() const;  ///< "file: path" (or "file" at the root)
    [[noreturn]] void fail(const std::string &what) const;

    bool has(const std::string &key) const;
    Field at(const std::string &key) const;       ///< required member (object expected)
    Field at(std::size_t index) const;            ///< array element
    std::size_t size() const;                     ///< array size (array expected)
    bool is_object() const { return node_->is_object(); }
    bool is_array() const { return node_->is_array(); }

    double as_number() const;
    int64_t as_int() const;
    std::string as_string() const;
    bool as_bool() const;

    double number(const std::string &key) const;
    double number_or(const std::string &key, double dflt) const;
    /** Number in [lo, hi] (or the default when absent). */
    double number_in(const std::string &key, double dflt, double lo, double hi) const;
    double number_req_in(const std::string &key, double lo, double hi) const;
    int64_t integer(const std::string &key) const;
    int64_t integer_or(const std::string &key, int64_t dflt) const;
    int64_t integer_in(const std::string &key, int64_t dflt, int64_t lo, int64_t hi) const;
    std::string string(const std::string &key) const;
    std::string string_or(const std::string &key, const std::string &dflt) const;
    /** One of the allowed strings (or the default when absent). */
    std::string choice_or(const std::string &key, const std::string &dflt,
                          std::initializer_list<const char *> allowed) const;
    bool boolean_or(const std::string &key, bool dflt) const;
    /** Array of exactly n numbers. */
    std::vector<double> numbers(const std::string &key, std::size_t n) const;

    /** InputError naming the first member not in `allowed` (catches typos in scenario files). */
    void only(std::initializer_list<const char *> allowed) const;
    /** The same over null-terminated name lists: a member must be in one of them. */
    void only(std::initializer_list<const char *const *> lists) const;

private:
    const json *node_;
    std::string file_;
    std::string path_;
    std::string child_path(const std::string &key) const;
};

}  // namespace pft::host
