// args.cpp - option parsing and the subcommand registry of fracdesign.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "fracdesign/cli.hpp"

namespace fracdesign {

Args::Args(const std::vector<std::string>& argv, const std::vector<std::string>& flags)
{
    auto is_flag = [&](const std::string& k) {
        for (const auto& f : flags)
            if (f == k) return true;
        return false;
    };
    for (size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
            std::string key = a.substr(2), val;
            size_t eq = key.find('=');
            if (eq != std::string::npos) {
                val = key.substr(eq + 1);
                key = key.substr(0, eq);
            } else if (is_flag(key)) {
                val = "1";
            } else {
                if (i + 1 >= argv.size()) throw UsageError("option --" + key + " needs a value");
                val = argv[++i];
            }
            opt_[key] = val;
        } else {
            pos_.push_back(a);
        }
    }
}

bool Args::has(const std::string& key) const { return opt_.count(key) != 0; }

std::string Args::str(const std::string& key, const std::string& def) const
{
    auto it = opt_.find(key);
    return it == opt_.end() ? def : it->second;
}

std::string Args::str(const std::string& key) const
{
    auto it = opt_.find(key);
    if (it == opt_.end()) throw UsageError("missing required option --" + key);
    return it->second;
}

static double parse_number(const std::string& key, const std::string& s)
{
    char* end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end == s.c_str() || *end != '\0' || !std::isfinite(v))
        throw UsageError("option --" + key + ": '" + s + "' is not a finite number");
    return v;
}

double Args::num(const std::string& key, double def) const
{
    auto it = opt_.find(key);
    return it == opt_.end() ? def : parse_number(key, it->second);
}

long Args::integer(const std::string& key, long def) const
{
    auto it = opt_.find(key);
    if (it == opt_.end()) return def;
    double v = parse_number(key, it->second);
    if (v != std::floor(v)) throw UsageError("option --" + key + ": '" + it->second + "' is not an integer");
    return static_cast<long>(v);
}

std::vector<double> Args::nums(const std::string& key) const
{
    std::vector<double> out;
    std::stringstream ss(str(key));
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(parse_number(key, item));
    return out;
}

void Args::check_known(const std::vector<std::string>& known) const
{
    for (const auto& kv : opt_) {
        bool ok = false;
        for (const auto& k : known) ok = ok || k == kv.first;
        if (!ok) throw UsageError("unknown option --" + kv.first);
    }
}

std::map<std::string, Command>& command_registry()
{
    static std::map<std::string, Command> reg;
    return reg;
}

std::string& command_program()
{
    static std::string name;
    return name;
}

CommandRegistrar::CommandRegistrar(Command c) { command_registry()[c.name] = std::move(c); }

void write_file(const std::string& path, const std::string& bytes)
{
    std::ofstream f(path, std::ios::binary);
    if (!f || !f.write(bytes.data(), static_cast<std::streamsize>(bytes.size())) || !f.flush())
        throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace fracdesign
