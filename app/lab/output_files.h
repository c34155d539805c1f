#pragma once
// The files each command writes into its output folder, by name: each command checks them all
// before its runs (prepareOutputFiles, command_line.h), and lab report checks those of every
// command it runs before the first. A file a command writes is listed here, or a folder in its
// place is found only after the work (`LabExit.EachCommandWritesOnlyTheFilesItChecksFirst` holds
// each list to what is written).
#include <filesystem>
#include <string>
#include <vector>

namespace lab {

/// sweep.cpp: results.csv, pareto.csv, sweep.gp and its chart.
std::vector<std::string> sweepFiles();
/// stability.cpp: the report, the CSV, the heat maps' data, script and pictures.
std::vector<std::string> stabilityFiles();
/// scale.cpp: scale.csv, scale.gp and its chart.
std::vector<std::string> scaleFiles();
/// converge.cpp: converge.csv, and each scene's chart script and pictures, named after the scene
/// (convergeChartNames).
std::vector<std::string> convergeFiles(const std::vector<std::string>& sceneNames);
/// converge.cpp: each scene's chart name, "converge-NAME", with any '/' made '-' and a number
/// after a name already taken, so that no chart writes over another.
std::vector<std::string> convergeChartNames(const std::vector<std::string>& sceneNames);
/// converge.cpp: the names of the scene files (names in `sceneDir`, or paths), as read.
std::vector<std::string> convergeSceneNames(const std::vector<std::string>& scenes,
                                            const std::filesystem::path& sceneDir);

}  // namespace lab
