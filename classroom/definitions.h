// classroom/definitions.h: where each function and struct of a C++ file is defined, found once for
// every reader of the lecture as text: the homework's cutter (a task's function, cut.cpp), the
// page's code view (`cut --index`, read by web/build_code.js) and the notes' tests (a cited name is
// defined where the page says). A definition is a function or struct whose line is indented by at
// most 4 spaces (free functions, struct members, a member defined outside as Rng::uniform) and
// whose body's braces are found in the code, comments and strings aside.
#pragma once
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

namespace definitions {

// The source as the compiler sees its structure: comments, strings and character literals blanked
// (same length, lines kept), so that braces and names are found only in code.
inline std::string codeOnly(const std::string& s) {
    std::string c = s;
    for (size_t i = 0; i < c.size(); ++i) {
        if (c[i] == '/' && i + 1 < c.size() && c[i + 1] == '/') {
            while (i < c.size() && c[i] != '\n') c[i++] = ' ';
        } else if (c[i] == '/' && i + 1 < c.size() && c[i + 1] == '*') {
            for (; i + 1 < c.size() && !(c[i] == '*' && c[i + 1] == '/'); ++i)
                if (c[i] != '\n') c[i] = ' ';
            if (i + 1 < c.size()) c[i] = c[i + 1] = ' ', ++i;
        } else if (c[i] == '"' || c[i] == '\'') {
            const char q = c[i];
            if (q == '\'' && i > 0 && std::isxdigit((unsigned char)c[i - 1])) continue;  // a digit separator
            for (++i; i < c.size() && c[i] != q; ++i) {
                if (c[i] == '\\') c[i++] = ' ';
                if (i < c.size() && c[i] != '\n') c[i] = ' ';
            }
        }
    }
    return c;
}

// The position of the bracket that closes the one at `open`, or npos.
inline size_t matching(const std::string& code, size_t open, char a, char b) {
    int depth = 0;
    for (size_t i = open; i < code.size(); ++i) {
        if (code[i] == a) ++depth;
        if (code[i] == b && --depth == 0) return i;
    }
    return std::string::npos;
}

struct Definition {
    std::string name;                     // as written: drawCoordinates's is "Rng::drawCoordinates"
    bool isStruct = false;
    int indent = 0;                       // 0: the file's top level
    int firstLine = 0, lastLine = 0;      // 1-based: the name's line and the closing brace's
    size_t paren = 0, close = 0;          // a function's parameter list (its parentheses)
    size_t open = 0, end = 0;             // the body's braces
};

inline bool isWordChar(char c) { return std::isalnum((unsigned char)c) || c == '_'; }

// Every definition of `source`, in the file's order.
inline std::vector<Definition> index(const std::string& source) {
    static const char* const kNotNames[] = {"if", "for", "while", "switch", "return", "sizeof", "catch", "decltype", "alignof",
                                            "static_assert", "defined", "operator"};
    const std::string code = codeOnly(source);
    std::vector<size_t> lineStarts = {0};
    for (size_t i = 0; i < code.size(); ++i)
        if (code[i] == '\n') lineStarts.push_back(i + 1);
    auto lineOf = [&](size_t at) { return int(std::upper_bound(lineStarts.begin(), lineStarts.end(), at) - lineStarts.begin()); };
    std::vector<Definition> found;
    for (size_t l = 0; l < lineStarts.size(); ++l) {
        const size_t start = lineStarts[l], stop = l + 1 < lineStarts.size() ? lineStarts[l + 1] - 1 : code.size();
        const size_t text = code.find_first_not_of(' ', start);
        if (text >= stop || text - start > 4 || !(std::isalpha((unsigned char)code[text]) || code[text] == '_' || code[text] == '[')) continue;
        Definition d;
        d.indent = int(text - start);
        const std::string line = code.substr(text, stop - text);
        if (line.rfind("struct ", 0) == 0 || line.rfind("class ", 0) == 0) {  // struct NAME ... {
            size_t n = text + line.find(' ') + 1, e = n;
            while (e < stop && isWordChar(code[e])) ++e;
            const size_t brace = code.find_first_of("{;", e);
            if (e == n || brace == std::string::npos || code[brace] != '{') continue;
            d.name = code.substr(n, e - n), d.isStruct = true, d.open = brace, d.end = matching(code, brace, '{', '}');
        } else {  // TYPE NAME(...) [const] {
            const size_t paren = code.find('(', text);
            if (paren >= stop || code.find('=', text) < paren) continue;
            size_t e = paren;
            while (e > text && code[e - 1] == ' ') --e;
            size_t b = e;
            while (b > text && (isWordChar(code[b - 1]) || code[b - 1] == ':')) --b;
            if (b == e || b == text || !std::isalpha((unsigned char)code[b])) continue;  // no name, or no type before it
            d.name = code.substr(b, e - b);
            bool keyword = false;
            for (const char* k : kNotNames) keyword = keyword || d.name == k || line.rfind(std::string(k) + " ", 0) == 0;
            if (keyword) continue;
            d.paren = paren, d.close = matching(code, paren, '(', ')');
            if (d.close == std::string::npos) continue;
            size_t next = code.find_first_not_of(" \n", d.close + 1);
            while (next != std::string::npos && (code.compare(next, 5, "const") == 0 || code.compare(next, 8, "noexcept") == 0))
                next = code.find_first_not_of(" \n", next + (code[next] == 'c' ? 5 : 8));
            if (next == std::string::npos || code[next] != '{') continue;  // a declaration or a call
            d.open = next, d.end = matching(code, next, '{', '}');
        }
        if (d.end == std::string::npos) continue;
        d.firstLine = int(l) + 1, d.lastLine = lineOf(d.end);
        found.push_back(d);
    }
    return found;
}

// A function's first definition at the file's top level, by its unqualified name.
inline bool topLevelFunction(const std::vector<Definition>& all, const std::string& name, Definition& d) {
    for (const Definition& x : all)
        if (!x.isStruct && x.indent == 0 && x.name == name) return d = x, true;
    return false;
}

}  // namespace definitions
