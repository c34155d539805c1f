#include "charts.h"

#include "command_line.h"
#include "fileio/files.h"
#include "fileio/printable.h"
#include "gnuplot.h"
#include "text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <system_error>
#include <utility>

namespace lab {
namespace {

// The most a drawn chart is read back: gnuplot's PNGs and SVGs of the lab's charts are under 1 MB.
constexpr std::size_t kMaxChartBytes = std::size_t{64} << 20;

// A new hidden folder PREFIXxxxxxx inside `parent`, removed with whatever is left in it when this
// goes.
class PrivateFolder {
 public:
  PrivateFolder(const std::filesystem::path& parent, const char* prefix) {
    std::string name = (parent / (std::string(prefix) + "XXXXXX")).string();
    if (::mkdtemp(name.data()) != nullptr)
      path_ = name;
    else
      error_ = errno;
  }
  PrivateFolder(const PrivateFolder&) = delete;
  PrivateFolder& operator=(const PrivateFolder&) = delete;
  ~PrivateFolder() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }  ///< empty if it could not be made
  int error() const { return error_; }                         ///< errno when it could not

 private:
  std::filesystem::path path_;
  int error_ = 0;
};

// Text on one line of a script: a control character becomes a space. A line break in a title
// (a scene's name) would end the line, and what followed would run as gnuplot commands.
std::string oneLine(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    if (fileio::isControl(static_cast<unsigned char>(c))) c = ' ';
  }
  return out;
}

// A gnuplot single-quoted string: nothing is special inside but the quote, written twice.
std::string quoted(const std::string& text) {
  return singleQuoted(oneLine(text), "''");
}

// A label inside a datablock is one double-quoted column: keep it free of quotes and breaks.
std::string labelColumn(const std::string& text) {
  std::string out = oneLine(text);
  std::replace(out.begin(), out.end(), '"', ' ');
  return "\"" + out + "\"";
}

bool drawable(const Chart& chart, const ChartPoint& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  return (!chart.logX || p.x > 0.0) && (!chart.logY || p.y > 0.0);
}

std::vector<ChartPoint> drawablePoints(const Chart& chart, const ChartSeries& s) {
  std::vector<ChartPoint> out;
  for (const ChartPoint& p : s.points) {
    if (drawable(chart, p)) out.push_back(p);
  }
  return out;
}

// Whether the chart has any point to draw (gnuplot fails on a chart without one).
bool hasPoints(const Chart& chart) {
  return std::any_of(chart.series.begin(), chart.series.end(),
                     [&](const ChartSeries& s) { return !drawablePoints(chart, s).empty(); });
}

// Point types that stay apart in print: filled circle, square, diamond, triangles, then open ones.
constexpr int kPointTypes[] = {7, 5, 13, 9, 11, 6, 4, 12, 8, 10, 1, 2, 3};

std::string seriesBlock(std::size_t index, const std::vector<ChartPoint>& points) {
  std::string out = "$s" + std::to_string(index) + " << EOD\n";
  // Every point drawn is finite (drawable), so formatNumber writes its %.17g, never words.
  for (const ChartPoint& p : points)
    out += formatNumber(p.x, 17) + " " + formatNumber(p.y, 17) + " " + labelColumn(p.label) + "\n";
  return out + "EOD\n";
}

std::string plotCommand(const Chart& chart, const std::vector<std::vector<ChartPoint>>& kept) {
  std::string plot;
  std::size_t styled = 0;  // point styles go to the series drawn as points, in order
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    if (kept[i].empty()) continue;
    const ChartSeries& s = chart.series[i];
    const std::string block = "$s" + std::to_string(i);
    std::string item = block + " using 1:2 ";
    if (s.line && !s.markers) {
      item += "with lines lw 2 lc 'black' title " + quoted(s.title);
    } else {
      const std::size_t k = styled++;
      const int type = kPointTypes[k % (sizeof kPointTypes / sizeof kPointTypes[0])];
      item += std::string(s.line ? "with linespoints lw 1.5" : "with points") + " pt " +
              std::to_string(type) + " ps 1.2 lc " + std::to_string(k + 1) + " title " + quoted(s.title);
    }
    plot += (plot.empty() ? "plot " : ", \\\n     ") + item;
    if (s.labels) {
      plot += ", \\\n     " + block + " using 1:2:3 with labels left offset 0.7,0.6 font ',8' notitle";
    }
  }
  for (std::size_t i = 0; i < chart.guides.size(); ++i) {
    const ChartGuide& g = chart.guides[i];
    plot += ", \\\n     " + formatNumber(g.y, 17) + " with lines dt " + std::to_string(2 + i) +
            " lw 1.5 lc 'gray40' title " + quoted(g.title);
  }
  return plot + "\n";
}

}  // namespace

Chart logChart(std::string title, std::string xLabel, std::string yLabel, bool logY, std::string output) {
  return {.title = std::move(title),
          .xLabel = std::move(xLabel),
          .yLabel = std::move(yLabel),
          .logX = true,
          .logY = logY,
          .output = std::move(output)};
}

std::string gnuplotScript(const Chart& chart) {
  std::vector<std::vector<ChartPoint>> kept;
  for (const ChartSeries& s : chart.series) kept.push_back(drawablePoints(chart, s));

  if (std::all_of(kept.begin(), kept.end(), [](const auto& points) { return points.empty(); })) {
    // A plot command with nothing to plot is no command: gnuplot failed on the `replot` left,
    // after it had opened (emptied) both pictures. This script runs, and says why it draws nothing.
    return "# " + oneLine(chart.title) +
           "\n# No point of this run can be drawn (none is finite, and positive " +
           "on a log axis), so this script draws nothing.\nprint " +
           quoted("nothing to draw: no point of " + chart.output + " is finite") + "\n";
  }
  std::string out = "# " + oneLine(chart.title) + "\n# Run gnuplot on this file in its folder: it writes " +
                    oneLine(chart.output) + ".png and " + oneLine(chart.output) +
                    ".svg. The data is inline, below.\n";
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (!kept[i].empty()) out += seriesBlock(i, kept[i]);
  }
  // noenhanced: names like gauss-seidel or "3x1" are text, not markup (_ and ^ are literal).
  out += "set termoption noenhanced\n";
  out += "set title " + quoted(chart.title) + "\n";
  out += "set xlabel " + quoted(chart.xLabel) + "\n";
  out += "set ylabel " + quoted(chart.yLabel) + "\n";
  if (chart.logX) out += "set logscale x\nset format x '%g'\n";
  if (chart.logY) out += "set logscale y\nset format y '%.0e'\n";
  out += "set grid xtics ytics mxtics mytics lc 'gray80'\n";
  out += "set key outside right top box\n";
  out += "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  out += std::string(kOutdirDefault);
  out += "set terminal pngcairo size 1000,640 font ',10' noenhanced\n";
  out += "set output outdir.'/'." + quoted(chart.output + ".png") + "\n";
  out += plotCommand(chart, kept);
  out += "set terminal svg size 1000,640 font ',10' noenhanced background 'white'\n";
  out += "set output outdir.'/'." + quoted(chart.output + ".svg") + "\n";
  out += "replot\n";
  out += "unset output\n";
  return out;
}

namespace {

// Whether a picture gnuplot drew is all there: a PNG ends with its IEND chunk, an SVG with its
// closing tag; other files are taken as they are.
bool whole(const std::string& file, std::string_view content) {
  if (file.ends_with(".png"))
    return content.starts_with("\x89PNG") && content.ends_with("IEND\xae\x42\x60\x82");
  if (file.ends_with(".svg"))
    return content.find("</svg>", content.size() > 64 ? content.size() - 64 : 0) != std::string_view::npos;
  return true;
}

}  // namespace

OutputFolder::OutputFolder(std::filesystem::path folder, const char* option)
    : folder_(std::move(folder)), option_(option) {
  prepareOutputFolder(folder_, option_);
}

void OutputFolder::write(const std::string& name, std::string content) {
  const auto same = [&](const auto& held) { return held.first == name; };
  if (const auto it = std::find_if(held_.begin(), held_.end(), same); it != held_.end()) {
    it->second = std::move(content);
    return;
  }
  held_.emplace_back(name, std::move(content));
}

std::string OutputFolder::draw(const std::string& name, const Chart& chart, const std::string& noPoints) {
  write(name, gnuplotScript(chart));
  const std::vector<std::string> outputs{chart.output + ".png", chart.output + ".svg"};
  if (!hasPoints(chart)) {
    stale_.insert(stale_.end(), outputs.begin(), outputs.end());
    return noPoints;
  }
  return render(name, outputs);
}

std::string OutputFolder::render(const std::string& name, const std::vector<std::string>& outputs) {
  if (findGnuplot().empty()) {
    stale_.insert(stale_.end(), outputs.begin(), outputs.end());
    return runGnuplot(folder_ / name, folder_);  // says how to draw them, and is no failure
  }
  std::string problem = drawInScratch(name, outputs);
  if (!problem.empty()) {
    stale_.insert(stale_.end(), outputs.begin(), outputs.end());
    failed_ = true;
  }
  return problem;
}

std::string OutputFolder::drawInScratch(const std::string& name, const std::vector<std::string>& outputs) {
  // The script reads its data by names relative to its folder: the scratch folder holds them all
  // but the charts drawn before, which no script reads.
  const PrivateFolder scratch(folder_, ".drawing-");
  if (scratch.path().empty()) {
    return "cannot create a folder to draw in, in " + folder_.string() + ": " +
           std::generic_category().message(scratch.error());
  }
  const auto isIn = [](const std::vector<std::string>& names, const std::string& file) {
    return std::find(names.begin(), names.end(), file) != names.end();
  };
  std::vector<std::string> given;
  std::vector<fileio::FileContent> inputs;
  for (const auto& [file, content] : held_) {
    if (isIn(drawn_, file)) continue;
    given.push_back(file);
    inputs.push_back({scratch.path() / file, content});
  }
  try {
    fileio::writeAllAtomically(inputs);
    if (std::string problem = runGnuplot(scratch.path() / name, scratch.path(), folder_ / name);
        !problem.empty())
      return problem;
    std::vector<std::string> drawn;
    for (const auto& entry : std::filesystem::directory_iterator(scratch.path())) {
      if (const std::string file = entry.path().filename().string(); !isIn(given, file))
        drawn.push_back(file);
    }
    std::sort(drawn.begin(), drawn.end());  // the listing's order is the file system's
    std::vector<std::pair<std::string, std::string>> pictures;
    pictures.reserve(drawn.size());
    for (const std::string& file : drawn)
      pictures.emplace_back(file, fileio::readWhole(scratch.path() / file, kMaxChartBytes));
    // gnuplot says nothing of a write that failed (a full disk, a file size limit) and exits 0.
    for (const std::string& output : outputs) {
      const auto it =
          std::find_if(pictures.begin(), pictures.end(), [&](const auto& p) { return p.first == output; });
      if (it == pictures.end())
        return "gnuplot did not draw " + output + " from " + (folder_ / name).string();
      if (!whole(output, it->second))
        return "gnuplot's " + output + " is cut short (" + std::to_string(it->second.size()) + " bytes)";
    }
    for (auto& [file, content] : pictures) {
      write(file, std::move(content));
      if (!isIn(drawn_, file)) drawn_.push_back(file);
    }
  } catch (const fileio::FileError& e) {
    return e.what();
  } catch (const std::filesystem::filesystem_error& e) {
    return e.what();
  }
  return {};
}

void OutputFolder::commit() {
  std::vector<fileio::FileContent> files;
  for (const auto& [name, content] : held_) files.push_back({folder_ / name, content});
  asOptionFailure(option_, [&] { fileio::writeAllAtomically(files); });
  for (const std::string& name : stale_) {
    std::error_code ignored;
    std::filesystem::remove(folder_ / name, ignored);
  }
  for (const auto& [name, content] : held_) written_.push_back((folder_ / name).string());
  held_.clear();
  stale_.clear();
  drawn_.clear();
}

}  // namespace lab
