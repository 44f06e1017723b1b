#include "json_field.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace pft::host {

json load_json_file(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open file");
    try {
        return json::parse(in, nullptr, true, /*ignore_comments=*/true);
    } catch (const json::parse_error &e) {
        throw InputError(path + ": invalid JSON (" + e.what() + ")");
    } catch (const json::exception &e) {
        // e.g. out_of_range 406: a number such as 1e999 that no double holds
        throw InputError(path + ": invalid JSON (" + e.what() + ")");
    }
}

namespace {
std::string brief(const json &j)
{
    std::string s = j.dump();
    if (s.size() > 40)
        s = s.substr(0, 37) + "...";
    return s;
}
}  // namespace

Field::Field(const json &node, std::string file, std::string path)
    : node_(&node), file_(std::move(file)), path_(std::move(path))
{
}

std::string Field::where() const { return path_.empty() ? file_ : file_ + ": " + path_; }

void Field::fail(const std::string &what) const { throw InputError(where() + ": " + what); }

std::string Field::child_path(const std::string &key) const
{
    return path_.empty() ? key : path_ + "." + key;
}

bool Field::has(const std::string &key) const
{
    return node_->is_object() && node_->contains(key) && !(*node_)[key].is_null();
}

Field Field::at(const std::string &key) const
{
    if (!node_->is_object())
        fail("expected an object, got " + brief(*node_));
    auto it = node_->find(key);
    if (it == node_->end())
        throw InputError(file_ + ": " + child_path(key) + ": missing required field");
    return Field(*it, file_, child_path(key));
}

Field Field::at(std::size_t index) const
{
    if (!node_->is_array())
        fail("expected an array, got " + brief(*node_));
    if (index >= node_->size())
        fail("index " + std::to_string(index) + " out of range");
    return Field((*node_)[index], file_, path_ + "[" + std::to_string(index) + "]");
}

std::size_t Field::size() const
{
    if (!node_->is_array())
        fail("expected an array, got " + brief(*node_));
    return node_->size();
}

double Field::as_number() const
{
    if (!node_->is_number())
        fail("expected a number, got " + brief(*node_));
    double v = node_->get<double>();
    if (!std::isfinite(v))
        fail("expected a finite number");
    return v;
}

int64_t Field::as_int() const
{
    if (node_->is_number_integer())
        return node_->get<int64_t>();
    if (node_->is_number_float()) {
        double v = node_->get<double>();
        if (std::isfinite(v) && std::floor(v) == v && std::fabs(v) < 9e15)
            return static_cast<int64_t>(v);
    }
    fail("expected an integer, got " + brief(*node_));
}

std::string Field::as_string() const
{
    if (!node_->is_string())
        fail("expected a string, got " + brief(*node_));
    return node_->get<std::string>();
}

bool Field::as_bool() const
{
    if (!node_->is_boolean())
        fail("expected true or false, got " + brief(*node_));
    return node_->get<bool>();
}

double Field::number(const std::string &key) const { return at(key).as_number(); }

double Field::number_or(const std::string &key, double dflt) const
{
    return has(key) ? number(key) : dflt;
}

double Field::number_in(const std::string &key, double dflt, double lo, double hi) const
{
    if (!has(key))
        return dflt;
    return number_req_in(key, lo, hi);
}

double Field::number_req_in(const std::string &key, double lo, double hi) const
{
    Field f = at(key);
    double v = f.as_number();
    if (v < lo || v > hi) {
        std::ostringstream os;
        os << "value " << v << " outside [" << lo << ", " << hi << "]";
        f.fail(os.str());
    }
    return v;
}

int64_t Field::integer(const std::string &key) const { return at(key).as_int(); }

int64_t Field::integer_or(const std::string &key, int64_t dflt) const
{
    return has(key) ? integer(key) : dflt;
}

int64_t Field::integer_in(const std::string &key, int64_t dflt, int64_t lo, int64_t hi) const
{
    if (!has(key))
        return dflt;
    Field f = at(key);
    int64_t v = f.as_int();
    if (v < lo || v > hi)
        f.fail("value " + std::to_string(v) + " outside [" + std::to_string(lo) + ", " +
               std::to_string(hi) + "]");
    return v;
}

std::string Field::string(const std::string &key) const { return at(key).as_string(); }

std::string Field::string_or(const std::string &key, const std::string &dflt) const
{
    return has(key) ? string(key) : dflt;
}

std::string Field::choice_or(const std::string &key, const std::string &dflt,
                             std::initializer_list<const char *> allowed) const
{
    if (!has(key))
        return dflt;
    Field f = at(key);
    std::string v = f.as_string();
    std::string list;
    for (const char *a : allowed) {
        if (v == a)
            return v;
        list += list.empty() ? "" : ", ";
        list += a;
    }
    f.fail("\"" + v + "\" is not one of: " + list);
}

bool Field::boolean_or(const std::string &key, bool dflt) const
{
    return has(key) ? at(key).as_bool() : dflt;
}

std::vector<double> Field::numbers(const std::string &key, std::size_t n) const
{
    Field f = at(key);
    if (f.size() != n)
        f.fail("expected " + std::to_string(n) + " numbers, got " + std::to_string(f.size()));
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = f.at(i).as_number();
    return v;
}

void Field::only(std::initializer_list<const char *> allowed) const
{
    std::vector<const char *> names(allowed);
    names.push_back(nullptr);
    only({names.data()});
}

void Field::only(std::initializer_list<const char *const *> lists) const
{
    if (!node_->is_object())
        fail("expected an object, got " + brief(*node_));
    for (auto it = node_->begin(); it != node_->end(); ++it) {
        bool ok = false;
        for (const char *const *l : lists)
            for (const char *const *a = l; *a != nullptr; ++a)
                ok = ok || it.key() == *a;
        if (!ok) {
            std::string list;
            for (const char *const *l : lists)
                for (const char *const *a = l; *a != nullptr; ++a)
                    list += (list.empty() ? "" : ", ") + std::string(*a);
            throw InputError(file_ + ": " + child_path(it.key()) +
                             ": unknown field (allowed here: " + list + ")");
        }
    }
}

}  // namespace pft::host
