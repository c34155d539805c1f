#include "stability_report.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "csv.h"
#include "gnuplot.h"

namespace lab::stability {
namespace {

// Beyond a factor of 1000 either way the colour says nothing more: a clean pass, or a blow-up.
constexpr double kLogClip = 3.0;

// The distinct values of one field of the settings, in first-seen order.
template <typename F>
std::vector<int> distinct(const std::vector<Setting>& settings, F field) {
  std::vector<int> out;
  for (const Setting& s : settings) addOnce(out, field(s));
  return out;
}

// Markdown table cells must not hold a bare '|'.
std::string cell(std::string text) {
  for (std::size_t i = text.find('|'); i != std::string::npos; i = text.find('|', i + 2))
    text.replace(i, 1, "\\|");
  return text;
}

// A Markdown table's header and the rule under it: the first column left-aligned, the others as
// `rule` aligns them ("---" left, "---:" right).
std::string tableHead(const std::vector<std::string>& columns, const std::string& rule = "---") {
  std::string head = "|", below = "|---|";
  for (const std::string& c : columns) head += " " + c + " |";
  for (std::size_t i = 1; i < columns.size(); ++i) below += rule + "|";
  return head + "\n" + below + "\n";
}

// A run's entry in a grid: the worst ratio, bold when the run failed. An infinite ratio of a
// finite figure is a body that never flipped under a flips min (min / 0): it did not blow up.
std::string gridEntry(const Outcome& o) {
  if (!o.judged) return "n/a";
  const Verdict& worst = o.verdicts[o.worst];
  const bool neverFlipped = std::isinf(worst.ratio) && std::isfinite(worst.value);
  const std::string r = neverFlipped ? "no flips" : formatRatio(worst.ratio);
  return o.passed ? r : "**" + r + "**";
}

std::string peerEntry(const Outcome& o) {
  if (!o.judged) return cell("n/a: " + o.note);
  std::string entry = gridEntry(o);
  std::vector<std::string> skipped;
  for (const Verdict& v : o.verdicts) {
    if (!v.judged) skipped.push_back(v.why);
  }
  if (!skipped.empty()) entry += " (n/a: " + join(skipped, "; ") + ")";
  return cell(entry);
}

// The columns of the settings in a method's block (settingGroup), in order.
std::vector<std::size_t> columnsOf(const SuiteResult& r, const std::string& method) {
  std::vector<std::size_t> columns;
  for (std::size_t k = 0; k < r.settings.size(); ++k) {
    if (settingGroup(r.settings[k]) == method) columns.push_back(k);
  }
  return columns;
}

void summaryTable(std::ostringstream& md, const SuiteResult& r) {
  std::vector<std::string> columns{"scene", "what must hold", "run"};
  columns.insert(columns.end(), r.methods.begin(), r.methods.end());
  columns.insert(columns.end(), r.peers.begin(), r.peers.end());
  columns.push_back("stepping");
  md << tableHead(columns);
  for (std::size_t s = 0; s < r.scenes.size(); ++s) {
    const SuiteScene& sc = r.scenes[s];
    std::vector<std::string> criteria;
    for (const Criterion& c : sc.criteria) criteria.push_back(c.describe());
    md << "| " << sc.name << " | " << cell(join(criteria, "; ")) << " | " << formatNumber(sc.steps * sc.dt)
       << " s, " << sc.steps << " steps |";
    for (const std::string& m : r.methods) {
      const std::vector<std::size_t> runs = columnsOf(r, m);
      const auto passed =
          std::count_if(runs.begin(), runs.end(), [&](std::size_t k) { return r.outcomes[s][k].passed; });
      md << " " << passed << "/" << runs.size() << " |";
    }
    for (std::size_t p = 0; p < r.peers.size(); ++p) {
      const Outcome& o = r.outcomes[s][r.settings.size() + p];
      md << " " << (!o.judged ? "n/a" : o.passed ? "pass" : "**fail**") << " |";
    }
    double ms = 0.0;  // the scene's stepping in World::step over all our runs (the peers' come after them)
    for (std::size_t k = 0; k < r.settings.size(); ++k) ms += r.outcomes[s][k].wallMs;
    md << " " << formatNumber(ms / 1000.0) << " s |\n";
  }
}

void methodGrid(std::ostringstream& md, const SuiteResult& r, const std::string& method) {
  const std::vector<std::size_t> columns = columnsOf(r, method);
  std::vector<std::string> head{"scene"};
  for (std::size_t k : columns) head.push_back(ixs(r.settings[k].iterations, r.settings[k].substeps));
  md << "\n### " << method << "\n\n" << tableHead(head, "---:");
  for (std::size_t s = 0; s < r.scenes.size(); ++s) {
    md << "| " << r.scenes[s].name << " |";
    for (std::size_t k : columns) md << " " << gridEntry(r.outcomes[s][k]) << " |";
    md << "\n";
  }
}

void peerTable(std::ostringstream& md, const SuiteResult& r) {
  md << "\n## Peers\n\n";
  if (r.peers.empty()) {
    md << "None: " << r.peerNote << ".\n";
    return;
  }
  md << "Each engine with its default solver at the scene's dt, judged on its bodies' poses after every "
        "step, measured alike for all: penetration and joint gaps by our geometry on those poses, speed at "
        "the bodies' particles' places, flips from the orientations (docs/lab.md, \"Peers\"). A peer's "
        "rigid bodies have no stick error of their own.\n\n";
  std::vector<std::string> columns{"scene"};
  columns.insert(columns.end(), r.peers.begin(), r.peers.end());
  md << tableHead(columns);
  for (std::size_t s = 0; s < r.scenes.size(); ++s) {
    md << "| " << r.scenes[s].name << " |";
    for (std::size_t p = 0; p < r.peers.size(); ++p)
      md << " " << peerEntry(r.outcomes[s][r.settings.size() + p]) << " |";
    md << "\n";
  }
}

template <typename F>
std::string matrix(const SuiteResult& r, F value) {
  std::ostringstream m;
  // The column labels: one token each, no spaces.
  m << "scene";
  for (const Setting& s : r.settings) {
    std::string group = settingGroup(s);
    std::replace(group.begin(), group.end(), ' ', '-');  // one token: "xpbd-rigid"
    m << " " << group << ":" << ixs(s.iterations, s.substeps);
  }
  for (const std::string& p : r.peers) m << " " << p;
  m << "\n";
  // gnuplot draws the first row at the bottom; the scenes are written last first so that the
  // chart reads top-down in the report's order.
  for (std::size_t s = r.scenes.size(); s-- > 0;) {
    // Quoted, as a name may hold spaces ("my scene" read as two columns broke the grid); gnuplot's
    // data files have no escape for a quote within quotes.
    std::string name = r.scenes[s].name;
    std::replace(name.begin(), name.end(), '"', '\'');
    m << '"' << name << '"';
    for (const Outcome& o : r.outcomes[s]) m << " " << value(o);
    m << "\n";
  }
  return m.str();
}

}  // namespace

std::string formatRatio(double ratio) {
  if (!std::isfinite(ratio)) return formatNumber(ratio);  // "n/a", or "blew up" for a blow-up
  // Three digits, or as many more as keep a failing 1.0004 from reading as a passing "1".
  std::string text;
  for (int digits = 3; digits <= 9; ++digits) {
    text = formatNumber(ratio, digits);
    if ((std::strtod(text.c_str(), nullptr) > 1.0) == (ratio > 1.0)) break;
  }
  return text;
}

std::string markdownReport(const SuiteResult& r) {
  std::ostringstream md;
  const std::size_t runs = r.scenes.size() * (r.settings.size() + r.peers.size());
  md << "# Stability suite\n\n"
     << r.scenes.size() << " scenes x " << r.settings.size() << " settings (methods " << join(r.methods, ", ")
     << "; iterations " << joinNumbers(distinct(r.settings, [](const Setting& s) { return s.iterations; }))
     << "; substeps " << joinNumbers(distinct(r.settings, [](const Setting& s) { return s.substeps; })) << ")"
     << (r.peers.empty() ? "" : " and the peers " + join(r.peers, ", ")) << ": " << runs << " runs in "
     << formatNumber(r.seconds) << " s.\n\n"
     << (r.jobs > 1
             ? "The suite runs " + std::to_string(r.jobs) + " at a time (--jobs " + std::to_string(r.jobs) +
                   "): each of our runs' ms_per_step and each scene's `stepping` are of a core shared "
                   "with other runs, not comparable with --jobs 1's.\n\n"
             : "")
     << (r.wholeRuns || r.settings.empty()
             ? ""
             : "A run of ours stops once a criterion has failed for good (past its limit, where no later "
               "step "
               "can bring it back; the CSV's note says at which step): its figures are those of the steps it "
               "ran, past the limit but no more than the whole run would read. --whole-runs steps every run "
               "to its end.\n\n")
     << (!r.settings.empty() && r.settings.front().model.options.sleep == true
             ? "Sleeping on (--sleep on): islands at rest sleep, ours and Bullet's.\n\n"
             : "")
     << "A run passes when every criterion of its scene holds over its window and the guard froze nothing. "
        "The method columns count the settings that pass; `stepping` is the scene's wall time in "
        "World::step over all its runs.\n\n";
  summaryTable(md, r);
  md << "\n## Per method\n\nColumns are iterations x substeps. Each entry is the worst criterion's value / "
        "limit (for flips, min / value or value / max; for stays-behind, the share of the way to the plane): "
        "at most 1 passes, **bold** fails, `blew up` is a blow-up (the guard froze a body), `no flips` a "
        "body that never flipped where a least number of flips was asked.\n";
  for (const std::string& m : r.methods) methodGrid(md, r, m);
  peerTable(md, r);
  return md.str();
}

std::string csvReport(const SuiteResult& r) {
  std::string csv =
      "scene,method,model,iterations,substeps,passed,blew_up,value,limit,ratio,criterion,ms_per_step,note\n";
  for (std::size_t s = 0; s < r.scenes.size(); ++s) {
    const SuiteScene& sc = r.scenes[s];
    for (std::size_t k = 0; k < r.outcomes[s].size(); ++k) {
      const Outcome& o = r.outcomes[s][k];
      std::vector<std::string> fields{csvField(sc.name)};
      if (k >= r.settings.size()) {  // a peer
        fields.insert(fields.end(), {csvField(r.peers[k - r.settings.size()]), "", "", ""});
      } else {
        const Setting& setting = r.settings[k];
        // A model imposed on a scene with no body changed nothing: not named as if it ran.
        fields.insert(fields.end(), {std::string(phys::toString(setting.method)),
                                     csvField(sc.boxes == 0 ? std::string() : setting.model.label),
                                     std::to_string(setting.iterations), std::to_string(setting.substeps)});
      }
      if (!o.judged) {
        fields.insert(fields.end(), {"n/a", "", "", "", "", ""});
      } else {
        const Criterion& c = sc.criteria[o.worst];
        const Verdict& v = o.verdicts[o.worst];
        // A flips criterion with only a max has min 0; its max is the limit then.
        const double limit = c.metric == Metric::Flips && c.limit <= 0.0 ? c.upper : c.limit;
        // A blow-up's figure is infinity: written blank, as every figure that is not finite. A run
        // stopped once it failed for good did not blow up in its steps, but might have in the
        // rest: blank, not known.
        const std::string blewUp = o.stoppedAt > 0 ? "" : std::isfinite(v.value) ? "0" : "1";
        fields.insert(fields.end(), {o.passed ? "1" : "0", blewUp, csvNumber(v.value, 6), formatLimit(limit),
                                     csvNumber(v.ratio, 6), csvField(c.describe())});
      }
      fields.insert(fields.end(), {csvNumber(o.msPerStep, 6), csvField(o.note)});
      csv += csvLine(fields);
    }
  }
  return csv;
}

std::string passMatrix(const SuiteResult& r) {
  return matrix(r, [](const Outcome& o) { return !o.judged ? "0.5" : o.passed ? "1" : "0"; });
}

std::string errorMatrix(const SuiteResult& r) {
  return matrix(r, [](const Outcome& o) {
    if (!o.judged) return std::string("NaN");
    const double ratio = o.verdicts[o.worst].ratio;
    const double log = ratio > 0.0 ? std::log10(ratio) : -kLogClip;  // 0 (no drift at all) is a clean pass
    return formatNumber(std::isnan(log) ? kLogClip : std::clamp(log, -kLogClip, kLogClip));
  });
}

// Each cell a filled box a unit wide at its column and row (gnuplot's `with image` draws nothing of
// a matrix of one row: a suite of one scene), one of no size where the value is NaN.
constexpr const char* kCells =
    "matrix rowheaders columnheaders using 1:2:($3 == $3 ? 0.5 : 0):($3 == $3 ? 0.5 : 0):3 "
    "with boxxyerror fillstyle solid noborder fillcolor palette";

std::string gnuplotScript(const SuiteResult& r) {
  const std::size_t columns = r.settings.size() + r.peers.size();
  // 22 pixels a cell, square, with fixed margins in pixels for the labels, the title and the
  // colour bar, so a run of two scenes reads as well as one of twenty-four.
  constexpr std::size_t kCell = 22, kRight = 130, kTop = 50, kBottom = 150;
  std::size_t longest = 0;  // the longest scene name sets the left margin (about 7 pixels a letter)
  for (const SuiteScene& sc : r.scenes) longest = std::max(longest, sc.name.size());
  const std::size_t kLeft = 40 + 7 * longest;
  // At least wide enough for the titles; extra width is left blank on the right, so cells stay square.
  const std::size_t plotRight = kLeft + kCell * columns;
  // The colour bar is at least kBar high, so that its labels stand apart for a suite of one scene.
  constexpr std::size_t kBar = 120;
  const std::size_t cells = kCell * r.scenes.size(), bar = std::max(cells, kBar);
  const std::size_t width = std::max<std::size_t>(plotRight + kRight, 760), height = kTop + kBottom + bar;
  auto at = [](std::size_t pixels, std::size_t of) {
    return formatNumber(static_cast<double>(pixels) / static_cast<double>(of));
  };
  // A title as a label from the left edge: a centred title overflows a narrow chart.
  const std::string titleY = at(height - 25, height);
  std::ostringstream gp;
  gp << "# Drawn by `lab stability --out DIR` (docs/lab.md); run `gnuplot stability.gp` in DIR to redraw.\n"
     << "# Scenes on y, solver settings (method:iterations x substeps) then peers on x.\n"
     << "unset key\nset xtics rotate by 90 right font ',8'\nset ytics font ',9'\nset tics scale 0\n"
     << "set lmargin at screen " << at(kLeft, width) << "\nset rmargin at screen " << at(plotRight, width)
     << "\nset bmargin at screen " << at(height - kTop - cells, height) << "\nset tmargin at screen "
     << at(height - kTop, height) << "\nset colorbox user origin screen " << at(plotRight + 12, width)
     << ", screen " << at(height - kTop - bar, height) << " size screen " << at(16, width) << ", screen "
     << at(bar, height)
     << "\n"
     // Cells not judged (NaN) are drawn as boxes of no size: a grey ground behind the cells shows them.
     << "set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 back fillcolor rgb '#bdbdbd' "
        "fillstyle solid noborder\n";
  // Lines between the methods' blocks of settings, and between the settings and the peers.
  for (std::size_t k = 1; k < columns; ++k) {
    const bool newBlock = k >= r.settings.size()
                              ? k == r.settings.size()
                              : settingGroup(r.settings[k]) != settingGroup(r.settings[k - 1]);
    const double x = static_cast<double>(k) - 0.5;  // between cell k - 1 and cell k
    if (newBlock)
      gp << "set arrow from " << x << ", graph 0 to " << x << ", graph 1 nohead front lw 2 lc rgb 'black'\n";
  }
  gp << kOutdirDefault << "do for [format in 'png svg'] {\n"
     << "  if (format eq 'png') { if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size "
     << width << "," << height << " } else { set terminal png size " << width << "," << height << " } }\n"
     << "  if (format eq 'svg') { set terminal svg size " << width << "," << height << " }\n"
     << "  set output outdir.'/stability-pass.'.format\n"
     << "  set label 1 'Stability: pass (green), fail (red), not judged (grey)' at screen 0.01, screen "
     << titleY << " left\n"
     << "  set cbrange [0:1]\n  set palette defined (0 '#d73027', 0.5 '#bdbdbd', 1 '#1a9850')\n"
     << "  set cbtics ('fail' 0, 'n/a' 0.5, 'pass' 1)\n  set palette maxcolors 3\n"
     << "  plot 'stability-pass.dat' " << kCells << "\n"
     << "  set output outdir.'/stability-error.'.format\n"
     << "  set label 1 'Stability: log10(value / limit) of the worst criterion: > 0 fails, 3 is 1000 or a "
        "blow-up, grey n/a' at screen 0.01, screen "
     << titleY << " left\n"
     << "  set cbrange [" << -kLogClip << ":" << kLogClip << "]\n"
     << "  set palette defined (-3 '#2166ac', -1 '#d1e5f0', 0 '#f7f7f7', 0.001 '#fddbc7', 1 '#ef8a62', 3 "
        "'#67001f')\n"
     << "  set cbtics autofreq\n  set palette maxcolors 0\n"
     << "  plot 'stability-error.dat' " << kCells << "\n"
     << "  unset output\n}\n";
  return gp.str();
}

}  // namespace lab::stability
