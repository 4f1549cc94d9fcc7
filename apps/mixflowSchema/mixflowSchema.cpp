// mixflowSchema: prints the Markdown tables of the declared dictionaries, and keeps the
// generated tables of a document (docs/parameters.md) equal to them.
//   mixflowSchema NAME          the table NAME (sceneProperties, sceneProperties.liquid, ...,
//                               plausible: the plausible ranges of every declared dictionary)
//   mixflowSchema -check DOC    exit 1 when a block <!-- BEGIN generated: NAME --> ...
//                               <!-- END generated --> of DOC differs from the declarations
//   mixflowSchema -update DOC   rewrites those blocks (the text around them is kept)
//   mixflowSchema -json         every declared entry of every dictionary file, with its type,
//                               default, range or words, unit and meaning, as one JSON object
//                               {file: {dotted entry: {...}}} (the Python package reads it:
//                               python/mixflow/schema.py)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "BulkMixtureCoeffs.h"
#include "BulkModel.h"
#include "CfdDict.h"
#include "CouplingProperties.h"
#include "DemDict.h"
#include "Dictionary.h"
#include "ExtractSettings.h"
#include "MixflowProperties.h"
#include "SceneProperties.h"

namespace {
using mixflow::Schema;

struct Table {
  std::string name;
  const Schema& schema;
  std::vector<std::string> sections;
};

std::vector<Table> tables() {
  return {
      {"sceneProperties",
       mixflow::SceneProperties::schema(),
       {"", "sample", "channel", "particles"}},
      {"sceneProperties.liquid", mixflow::SceneProperties::schema(), {"liquid", "liquid.air"}},
      {"sceneProperties.gate", mixflow::SceneProperties::schema(), {"gate"}},
      {"demDict", mixflow::DemDict::schema(), {"", "velocityProfile", "savage", "settle"}},
      {"cfdDict", mixflow::CfdDict::schema(), {"", "observables"}},
      {"mixflowProperties", mixflow::MixflowProperties::schema(), {""}},
      {"couplingProperties", mixflow::coupling::CouplingProperties::schema(), {""}},
      {"bulkProperties", mixflow::cfd::BulkModel::schema(), {"", "drifts", "solid", "basal"}},
      {"bulkMixtureCoeffs", mixflow::BulkMixtureCoeffs::schema(), {""}},
      {"extractDict",
       mixflow::mx::ExtractSettings::schema(),
       {"", "grid", "windows", "thresholds", "viscosity", "fluid", "particles", "kernel",
        "regions.<name>"}},
  };
}

// The table "plausible": every declared entry with a plausible range (Param::plausible), of
// every dictionary above.
const std::string kPlausible = "plausible";
std::string plausibleTable() {
  std::string s =
      "| file | entry | plausible | unit | of | unit slips suggested |\n"
      "|---|---|---|---|---|---|\n";
  std::set<const Schema*> done;
  for (const auto& t : tables())
    if (done.insert(&t.schema).second) s += t.schema.plausibleRows();
  return s;
}

// The tables by name: the declared dictionaries' and "plausible".
std::vector<std::pair<std::string, std::string>> namedTables() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& t : tables()) out.emplace_back(t.name, t.schema.markdown(t.sections));
  out.emplace_back(kPlausible, plausibleTable());
  return out;
}

const std::string kEnd = "<!-- END generated -->";
std::string beginMarker(const std::string& name) {
  return "<!-- BEGIN generated: " + name + " -->";
}

// DOC with every generated block replaced by the declarations' table; `stale` gets the names of
// the blocks that differed, `missing` those of the tables DOC has no block for.
std::string regenerate(const std::string& doc, std::vector<std::string>& stale,
                       std::vector<std::string>& missing) {
  std::string out = doc;
  for (const auto& [name, table] : namedTables()) {
    const std::string begin = beginMarker(name) + "\n";
    const size_t b = out.find(begin);
    const size_t e = b == std::string::npos ? b : out.find(kEnd, b);
    if (b == std::string::npos || e == std::string::npos) {
      missing.push_back(name);
      continue;
    }
    const size_t from = b + begin.size();
    if (out.compare(from, e - from, table) != 0) stale.push_back(name);
    out.replace(from, e - from, table);
  }
  return out;
}

// Sections of a declared dictionary that no table shows: an entry added there would be missing
// from the document without any block going stale.
std::vector<std::string> unlisted() {
  std::vector<std::string> out;
  std::set<std::pair<const Schema*, std::string>> shown;
  for (const auto& t : tables())
    for (const auto& sec : t.sections) shown.insert({&t.schema, sec});
  std::set<std::pair<const Schema*, std::string>> reported;
  for (const auto& t : tables())
    for (const auto& p : t.schema.params()) {
      if (p.type == mixflow::Param::Type::Dict) continue;
      const std::pair<const Schema*, std::string> key{&t.schema, p.section()};
      if (shown.count(key) || !reported.insert(key).second) continue;
      out.push_back(t.schema.file() + ": section '" + p.section() + "' (entry '" + p.path +
                    "') is declared but shown in no table of mixflowSchema");
    }
  return out;
}

// JSON text of a string: quotes, backslashes and control characters escaped.
std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// JSON number of v: the fewest significant digits that read back as v; null when not finite.
std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string jsonWords(const std::vector<std::string>& words) {
  std::string out = "[";
  for (size_t i = 0; i < words.size(); ++i) out += (i ? ", " : "") + jsonString(words[i]);
  return out + "]";
}

std::string jsonRange(const mixflow::Range& r) {
  return "{\"lo\": " + jsonNumber(r.lo) + ", \"hi\": " + jsonNumber(r.hi) +
         ", \"loOpen\": " + (r.loOpen ? "true" : "false") +
         ", \"hiOpen\": " + (r.hiOpen ? "true" : "false") + "}";
}

const char* typeName(mixflow::Param::Type type) {
  using T = mixflow::Param::Type;
  static const std::pair<T, const char*> kNames[] = {
      {T::Scalar, "scalar"}, {T::Integer, "integer"}, {T::Word, "word"}, {T::Switch, "switch"},
      {T::Text, "text"},     {T::Dict, "dict"},       {T::Any, "any"}};
  for (const auto& [t, name] : kNames)
    if (t == type) return name;
  return "any";
}

// One declared entry: type, required, auto, default (null where there is none: a required
// entry, a sub-dictionary, an entry another reader reads, a default taken from elsewhere, which
// defaultNote names), range (scalar, integer), words (word; empty: any word), the plausible
// range of the material it names (plausible, plausibleFor) where it declares one.
std::string jsonParam(const mixflow::Param& p) {
  using T = mixflow::Param::Type;
  std::string def = "null";
  if (!p.required && !p.autoDefault && p.defaultNote.empty()) {
    if (p.type == T::Scalar || p.type == T::Integer) def = jsonNumber(p.number);
    if (p.type == T::Switch) def = p.number != 0 ? "true" : "false";
    if (p.type == T::Word || p.type == T::Text) def = jsonString(p.word);
  }
  std::string out = std::string("{\"type\": \"") + typeName(p.type) + "\"" +
                    ", \"required\": " + (p.required ? "true" : "false") +
                    ", \"auto\": " + (p.autoDefault ? "true" : "false") + ", \"default\": " + def;
  if (p.type == T::Scalar || p.type == T::Integer) out += ", \"range\": " + jsonRange(p.range);
  if (p.plausibleRange)
    out += ", \"plausible\": " + jsonRange(*p.plausibleRange) +
           ", \"plausibleFor\": " + jsonString(p.plausibleFor);
  if (p.type == T::Word) out += ", \"words\": " + jsonWords(p.words);
  if (!p.onlyFor.empty()) out += ", \"onlyFor\": " + jsonWords(p.onlyFor);
  if (!p.defaultNote.empty()) out += ", \"defaultNote\": " + jsonString(p.defaultNote);
  return out + ", \"unit\": " + jsonString(p.unit) + ", \"meaning\": " + jsonString(p.meaning) +
         "}";
}

// Every declared dictionary file once (sceneProperties has two tables), in the tables' order.
std::string json() {
  std::string out = "{";
  std::set<const Schema*> done;
  for (const auto& t : tables()) {
    if (!done.insert(&t.schema).second) continue;
    out += std::string(done.size() > 1 ? ",\n " : "\n ") + jsonString(t.schema.file()) + ": {";
    const auto& params = t.schema.params();
    for (size_t i = 0; i < params.size(); ++i)
      out += std::string(i ? ",\n  " : "\n  ") + jsonString(params[i].path) + ": " +
             jsonParam(params[i]);
    out += "}";
  }
  return out + "\n}\n";
}

int usage() {
  std::cerr << "usage: mixflowSchema NAME | -check DOC | -update DOC | -json\n  NAME:";
  for (const auto& [name, table] : namedTables()) std::cerr << " " << name;
  std::cerr << "\n";
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 1 && args[0] == "-json") {
      std::cout << json();
      return 0;
    }
    if (args.size() == 1) {
      for (const auto& [name, table] : namedTables())
        if (name == args[0]) {
          std::cout << table;
          return 0;
        }
      return usage();
    }
    if (args.size() != 2 || (args[0] != "-check" && args[0] != "-update")) return usage();
    const std::string& path = args[1];
    const std::vector<std::string> hidden = unlisted();
    for (const auto& h : hidden) std::cerr << h << "\n";
    if (!hidden.empty()) return 1;
    std::vector<std::string> stale, missing;
    const std::string doc = mixflow::readTextFile(path);
    const std::string fresh = regenerate(doc, stale, missing);
    for (const auto& m : missing)
      std::cerr << path << ": no block " << beginMarker(m) << " ... " << kEnd << "\n";
    if (!missing.empty()) return 1;
    if (args[0] == "-update") {
      if (fresh != doc) std::ofstream(path) << fresh;
      std::cout << path << ": " << stale.size() << " generated table(s) rewritten\n";
      return 0;
    }
    for (const auto& s : stale)
      std::cerr << path << ": the table '" << s
                << "' differs from the declarations; regenerate it with: " << argv[0] << " -update "
                << path << "\n";
    if (!stale.empty()) return 1;
    std::cout << path << ": every generated table matches the declarations\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mixflowSchema: " << e.what() << "\n";
    return 1;
  }
}
