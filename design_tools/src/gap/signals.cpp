// signals.cpp - signal records for the gap diagnosis (see signals.hpp). The
// file format is the project's strict signal CSV (fracdesign/io/signal_csv.hpp).
#include "fracdesign/gap/signals.hpp"

#include <algorithm>
#include <stdexcept>

#include "fracdesign/io/signal_csv.hpp"

namespace fracdesign {
namespace gap {

bool Signals::has(const std::string& name) const
{
    return std::find(names.begin(), names.end(), name) != names.end();
}

Eigen::VectorXd Signals::col(const std::string& name) const
{
    auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw std::runtime_error(source + ": no signal named '" + name + "'");
    return values.col(it - names.begin());
}

Signals Signals::slice(Eigen::Index first, Eigen::Index n) const
{
    Signals s = *this;
    s.values = values.middleRows(first, n);
    s.t0 = t0 + double(first) * Ts;
    return s;
}

namespace {

// The reader options of every record the diagnosis takes: at least 3 rows.
io::SignalCsvOptions record_options()
{
    io::SignalCsvOptions opt;
    opt.min_rows = 3;
    return opt;
}

Signals from_table(const io::SignalTable& tab, const std::string& source)
{
    Signals s;
    s.source = source;
    s.names = tab.names;
    s.Ts = tab.dt;
    s.t0 = tab.t.front();
    s.values.resize(Eigen::Index(tab.size()), Eigen::Index(tab.names.size()));
    for (size_t j = 0; j < tab.columns.size(); ++j)
        s.values.col(Eigen::Index(j)) = Eigen::Map<const Eigen::VectorXd>(tab.columns[j].data(), Eigen::Index(tab.size()));
    return s;
}

}  // namespace

Signals load_signals(const std::string& path) { return from_table(io::read_signal_csv(path, record_options()), path); }

Signals signals_from_csv_text(const std::string& text, const std::string& origin)
{
    return from_table(io::parse_signal_csv(text, origin, record_options()), origin);
}

}  // namespace gap
}  // namespace fracdesign
