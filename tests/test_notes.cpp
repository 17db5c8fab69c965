// The lecture notes cannot rot: every function they cite exists in bdpt.cpp, every command they
// show runs (at 1 sample per pixel and 8x8 pixels), every make target exists, every figure they
// show is in lecture_notes/figures/. (Issue: lecture notes.)
#include "helpers.h"
#include <dirent.h>
#include <regex>

static std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

static std::vector<std::string> notePages() {
    std::vector<std::string> pages;
    DIR* dir = opendir("lecture_notes");
    for (dirent* e; dir && (e = readdir(dir));) {
        std::string n = e->d_name;
        if (n.size() > 3 && n.substr(n.size() - 3) == ".md") pages.push_back("lecture_notes/" + n);
    }
    if (dir) closedir(dir);
    std::sort(pages.begin(), pages.end());
    return pages;
}

TEST_CASE("the notes cite only functions that bdpt.cpp defines") {
    std::string source = slurp("bdpt.cpp");
    std::vector<std::string> pages = notePages();
    CHECK(pages.size() >= 16);  // 15 pages and the index
    int cited = 0;
    std::regex call("`([A-Za-z_][A-Za-z0-9_]*)\\(\\)`");
    for (const std::string& page : pages) {
        std::string text = slurp(page);
        for (std::sregex_iterator it(text.begin(), text.end(), call), end; it != end; ++it) {
            std::string name = (*it)[1];
            std::regex definition("\\ninline [^\\n(]*\\b" + name + "\\(");
            CAPTURE(page);
            CAPTURE(name);
            CHECK(std::regex_search(source, definition));
            ++cited;
        }
    }
    CHECK(cited > 40);
}

// A shown command, made quick: 1 sample per pixel, 8x8 pixels, files into build/notes/.
static std::vector<std::string> quickArgs(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words, args;
    for (std::string w; in >> w;) words.push_back(w);
    auto intoBuild = [](const std::string& path) { return "build/notes/" + path.substr(path.find_last_of('/') + 1); };
    for (size_t i = 1; i < words.size(); ++i) {
        const std::string& w = words[i];
        bool hasValue = i + 1 < words.size();
        if ((w == "--spp" || w == "--time" || w == "--res") && hasValue) { ++i; continue; }
        if ((w == "--out" || w == "--strategies") && hasValue) { args.push_back(w); args.push_back(intoBuild(words[++i])); continue; }
        args.push_back(w);
    }
    args.insert(args.end(), {"--spp", "1", "--res", "8x8", "--quiet"});
    return args;
}

TEST_CASE("every command the notes show runs") {
    std::system("mkdir -p build/notes");
    int commands = 0;
    for (const std::string& page : notePages()) {
        std::istringstream in(slurp(page));
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("./bdpt ", 0) != 0) continue;
            std::vector<std::string> args = quickArgs(line);
            for (size_t i = 0; i + 1 < args.size(); ++i)
                if (args[i] == "--strategies") std::system(("mkdir -p " + args[i + 1]).c_str());
            std::ostringstream so, se;
            CAPTURE(page);
            CAPTURE(line);
            CAPTURE(se.str());
            CHECK(runCommandLine(args, so, se) == 0);
            ++commands;
        }
    }
    CHECK(commands >= 20);
}

TEST_CASE("every make target and every figure the notes mention exists") {
    std::string makefile = slurp("Makefile");
    std::regex target("`make ([a-z-]+)`"), image("\\]\\((figures/[^)]+)\\)");
    int targets = 0, images = 0;
    for (const std::string& page : notePages()) {
        std::string text = slurp(page);
        for (std::sregex_iterator it(text.begin(), text.end(), target), end; it != end; ++it) {
            CAPTURE((*it)[1].str());
            CHECK(makefile.find("\n" + (*it)[1].str() + ":") != std::string::npos);
            ++targets;
        }
        for (std::sregex_iterator it(text.begin(), text.end(), image), end; it != end; ++it) {
            CAPTURE(page);
            CAPTURE((*it)[1].str());
            CHECK(fileExists("lecture_notes/" + (*it)[1].str()));
            ++images;
        }
    }
    CHECK(targets >= 3);
    CHECK(images >= 20);
}

TEST_CASE("every method has its own colour and line style in the charts, the same in every chart") {
    std::system("bash tests/charts.sh styles > build/tmp_styles.txt");
    std::istringstream in(slurp("build/tmp_styles.txt"));
    std::set<std::string> styles, labels;
    for (std::string line; std::getline(in, line);) {
        labels.insert(line.substr(0, line.find(' ')));
        styles.insert(line.substr(line.find(' ') + 1));
        CHECK(line.find("#999999") == std::string::npos);  // the fallback: a method without its own style
    }
    CHECK(labels.size() == 11);
    CHECK(styles.size() == labels.size());
}
