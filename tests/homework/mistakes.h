// The plausible mistakes of tests/homework/mistakes.txt, as that file writes them: read by
// make test-homework (which grades each) and by make test (test_lecture: each text it pins is in
// bdpt.cpp once, so that an edit of the lecture that moves one fails in seconds, not minutes).
#pragma once
#include <fstream>
#include <stdexcept>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

struct Mistake {
    std::string kind, task, what, words;
    std::vector<std::pair<std::string, std::string>> edits;  // replace, with
    std::vector<std::string> never;  // words the diagnosis must not hold (another mistake's)
};
inline std::vector<Mistake> readMistakes(const std::string& path = "tests/homework/mistakes.txt") {
    std::vector<Mistake> list;
    std::ifstream file(path);
    std::string* open = nullptr;
    for (std::string line; std::getline(file, line);) {
        if (line.empty() || line[0] == '#') { open = nullptr; continue; }
        if (line.rfind("mistake ", 0) == 0 || line.rfind("robust ", 0) == 0 || line.rfind("hidden ", 0) == 0) {
            Mistake m;
            m.kind = line.substr(0, line.find(' '));
            std::vector<std::string> parts;
            std::stringstream fields(line.substr(m.kind.size() + 1));
            for (std::string f; std::getline(fields, f, '|');) parts.push_back(f.substr(f.find_first_not_of(' '), f.find_last_not_of(' ') - f.find_first_not_of(' ') + 1));
            if (parts.size() != 3) throw std::runtime_error(path + ": '" + line + "' is not 'mistake TASK | what | words'");
            m.task = parts[0], m.what = parts[1], m.words = parts[2];
            list.push_back(m);
            open = nullptr;
        } else if (line.rfind("  replace ", 0) == 0 && !list.empty()) {
            list.back().edits.push_back({line.substr(10), ""});
            open = &list.back().edits.back().first;
        } else if (line.rfind("  never ", 0) == 0 && !list.empty()) {
            list.back().never.push_back(line.substr(8));
            open = nullptr;
        } else if (line.rfind("  with ", 0) == 0 && !list.empty() && !list.back().edits.empty()) {
            list.back().edits.back().second = line.substr(7);
            open = &list.back().edits.back().second;
        } else if (open) {
            *open += "\n" + line;
        }
    }
    return list;
}
