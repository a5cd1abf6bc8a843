#pragma once

// A small RAII wrapper over SQLite's C API: one Database per thread, statements prepared per
// call. Every error names the database file and the statement that failed.
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace tilejet::jobs {

class StoreError : public std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Statement;

class Database {
  public:
    // Opens (creating) the file in WAL mode with synchronous=FULL: a commit is on disk before
    // the line is told anything, so a power cut cannot lose a "sent" record (exactly-once rests
    // on it).
    explicit Database(const std::string& path);
    ~Database();
    Database(const Database&) = delete;
    Database& operator=(const Database&) = delete;

    void exec(std::string_view sql);
    Statement prepare(std::string_view sql);
    std::int64_t last_insert_rowid() const;
    int changes() const;
    const std::string& path() const { return path_; }
    [[noreturn]] void fail(std::string_view what) const;

  private:
    sqlite3* db_ = nullptr;
    std::string path_;
};

// One prepared statement; bind by 1-based position, step until it returns false.
class Statement {
  public:
    Statement(Database& db, sqlite3_stmt* stmt, std::string sql);
    ~Statement();
    Statement(Statement&& other) noexcept;
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;
    Statement& operator=(Statement&&) = delete;

    Statement& bind(int index, std::int64_t value);
    Statement& bind(int index, double value);
    Statement& bind(int index, std::string_view value);
    Statement& bind_null(int index);
    // True while a row is available.
    bool step();
    void run() {
        while (step()) {
        }
    }
    // Ready to bind and step again (bindings are kept).
    void reset();

    std::int64_t integer(int column) const;
    double real(int column) const;
    std::string text(int column) const;
    bool is_null(int column) const;

  private:
    Database* db_;
    sqlite3_stmt* stmt_;
    std::string sql_;
};

// BEGIN IMMEDIATE ... COMMIT, rolled back when left by an exception.
class Transaction {
  public:
    explicit Transaction(Database& db);
    ~Transaction();
    void commit();

  private:
    Database& db_;
    bool done_ = false;
};

}  // namespace tilejet::jobs
