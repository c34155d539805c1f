#include "charts.h"

#include "command_line.h"
#include "fileio/files.h"
#include "gnuplot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace lab {
namespace {

// A gnuplot single-quoted string: nothing is special inside but the quote, written twice.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// A label inside a datablock is one double-quoted column: keep it free of quotes and breaks.
std::string labelColumn(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += (c == '"' || c == '\n' || c == '\r') ? ' ' : c;
  return out + "\"";
}

std::string exact(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
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

// Point types that stay apart in print: filled circle, square, diamond, triangles, then open ones.
constexpr int kPointTypes[] = {7, 5, 13, 9, 11, 6, 4, 12, 8, 10, 1, 2, 3};

std::string seriesBlock(std::size_t index, const std::vector<ChartPoint>& points) {
  std::string out = "$s" + std::to_string(index) + " << EOD\n";
  for (const ChartPoint& p : points) out += exact(p.x) + " " + exact(p.y) + " " + labelColumn(p.label) + "\n";
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
  if (chart.guide) {
    plot += ", \\\n     " + exact(*chart.guide) + " with lines dt 2 lw 1.5 lc 'gray40' title " +
            quoted(chart.guideTitle);
  }
  return plot + "\n";
}

}  // namespace

Chart logChart(std::string title, std::string xLabel, std::string yLabel, bool logY, std::string output) {
  Chart chart;
  chart.title = std::move(title);
  chart.xLabel = std::move(xLabel);
  chart.yLabel = std::move(yLabel);
  chart.logX = true;
  chart.logY = logY;
  chart.output = std::move(output);
  return chart;
}

bool hasPoints(const Chart& chart) {
  return std::any_of(chart.series.begin(), chart.series.end(),
                     [&](const ChartSeries& s) { return !drawablePoints(chart, s).empty(); });
}

std::string gnuplotScript(const Chart& chart) {
  std::vector<std::vector<ChartPoint>> kept;
  for (const ChartSeries& s : chart.series) kept.push_back(drawablePoints(chart, s));

  std::string out = "# " + chart.title + "\n# Run gnuplot on this file in its folder: it writes " +
                    chart.output + ".png and " + chart.output + ".svg. The data is inline, below.\n";
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

OutputFolder::OutputFolder(std::filesystem::path folder, const char* option)
    : folder_(std::move(folder)), option_(option) {
  prepareOutputFolder(folder_, option_);
}

void OutputFolder::write(const std::string& name, std::string_view content) {
  try {
    fileio::writeAtomically(folder_ / name, content);
  } catch (const fileio::FileError& e) {
    throw CommandFailure(std::string(option_) + ": " + e.what());
  }
  list(name);
}

std::string OutputFolder::draw(const std::string& name, const Chart& chart, const std::string& noPoints) {
  write(name, gnuplotScript(chart));
  if (!hasPoints(chart)) {
    // No chart of these figures: one an earlier run drew here would stand beside CSVs it does not show.
    std::error_code ignored;
    std::filesystem::remove(folder_ / (chart.output + ".png"), ignored);
    std::filesystem::remove(folder_ / (chart.output + ".svg"), ignored);
    return noPoints;
  }
  std::string problem = runGnuplot(folder_ / name, folder_);
  if (problem.empty()) {
    list(chart.output + ".png");
    list(chart.output + ".svg");
  }
  failed_ = failed_ || (!problem.empty() && !findGnuplot().empty());
  return problem;
}

}  // namespace lab
