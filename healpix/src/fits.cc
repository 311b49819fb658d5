#include "zhf/healpix/fits.h"

#include <fitsio.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "zhf/healpix/limits.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/read_file.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::healpix {
namespace {

using io::excerpt;
using io::InputError;
using io::throw_if_interrupted;

constexpr long long kFitsBlock = 2880;
// Integers a header may hold (18 digits: never wraps a long long).
constexpr long long kLargestInteger = 999999999999999999LL;
// Values read or written per cfitsio call: the interrupt flag is polled between them.
constexpr long long kPixelsPerCall = 1 << 20;
// healpy's row length; a map shorter or not a multiple of it is written one value a row.
constexpr long long kValuesPerRow = 1024;

bool power_of_two(std::int64_t n) { return n > 0 && (n & (n - 1)) == 0; }

// cfitsio's short text for a status, its message stack cleared (cfitsio never prints by itself).
std::string fits_text(int status) {
  char text[FLEN_STATUS] = {};
  fits_get_errstatus(status, text);
  fits_clear_errmsg();
  return text;
}

struct FitsCloser {
  void operator()(fitsfile* f) const {
    int status = 0;
    fits_close_file(f, &status);
    fits_clear_errmsg();
  }
};
using FitsFile = std::unique_ptr<fitsfile, FitsCloser>;

std::string trimmed(const char* text) {
  std::string s(text);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// A header's "KEYWORD = value" cards, parsed here: cfitsio's value parsers are never given
// hostile text (one overruns a buffer on a malformed integer).
class Cards {
 public:
  explicit Cards(const std::string& source) : source_(source) {}
  void add(std::string key, std::string value) { cards_.emplace_back(std::move(key), std::move(value)); }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(source_ + ": " + what); }

  // An integer: optional sign, up to 18 digits, then blanks or a '/' comment.
  std::optional<long long> integer(const std::string& key, long long lo, long long hi) const {
    const std::string* v = find(key);
    if (!v) return std::nullopt;
    std::size_t i = v->find_first_not_of(' ');
    if (i == std::string::npos) fail(key + " is not an integer");
    const bool negative = (*v)[i] == '-';
    if ((*v)[i] == '+' || (*v)[i] == '-') ++i;
    const std::size_t digits = i;
    long long n = 0;
    while (i < v->size() && (*v)[i] >= '0' && (*v)[i] <= '9' && i - digits < 18) n = n * 10 + ((*v)[i++] - '0');
    const std::size_t end = v->find_first_not_of(' ', i);
    if (i == digits || (end != std::string::npos && (*v)[end] != '/')) fail(key + " is not an integer");
    n = negative ? -n : n;
    if (n < lo || n > hi) fail(key + " " + std::to_string(n) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return n;
  }
  // A finite decimal number (FITS's D exponent too), then blanks or a '/' comment.
  double number(const std::string& key) const {
    const std::string* v = find(key);
    std::size_t start = v ? v->find_first_not_of(' ') : std::string::npos;
    if (start == std::string::npos) fail(key + " is not a number");
    std::size_t end = v->find_first_of(" /", start);
    std::string token = v->substr(start, end == std::string::npos ? std::string::npos : end - start);
    std::replace(token.begin(), token.end(), 'D', 'E');
    const bool plain = !token.empty() && token.size() < 40 && token.find_first_not_of("0123456789+-.E") == std::string::npos;
    char* parsed = nullptr;
    const double x = plain ? std::strtod(token.c_str(), &parsed) : 0;
    const std::size_t rest = end == std::string::npos ? std::string::npos : v->find_first_not_of(' ', end);
    if (!plain || parsed != token.c_str() + token.size() || !std::isfinite(x) || (rest != std::string::npos && (*v)[rest] != '/'))
      fail(key + " is not a number");
    return x;
  }
  std::vector<std::string> keys() const {
    std::vector<std::string> out;
    for (const auto& card : cards_) out.push_back(card.first);
    return out;
  }
  // A quoted string ('' inside is a quote), trailing blanks dropped.
  std::optional<std::string> text(const std::string& key) const {
    const std::string* v = find(key);
    if (!v) return std::nullopt;
    std::size_t i = v->find_first_not_of(' ');
    if (i == std::string::npos || (*v)[i] != '\'') fail(key + " is not a quoted string");
    std::string out;
    for (++i;; ++i) {
      if (i >= v->size()) fail(key + " is not a quoted string");
      if ((*v)[i] == '\'') {
        if (i + 1 < v->size() && (*v)[i + 1] == '\'') {
          out += '\'', ++i;
          continue;
        }
        break;
      }
      out += (*v)[i];
    }
    return trimmed(out.c_str());
  }

 private:
  const std::string* find(const std::string& key) const {
    for (const auto& [k, v] : cards_)
      if (k == key) return &v;
    return nullptr;
  }
  const std::string& source_;
  std::vector<std::pair<std::string, std::string>> cards_;
};

// The primary header and the first extension's, card by card, before cfitsio reads them (cfitsio
// sizes its column tables from TFIELDS unchecked). `head` is the file's first bytes up to the
// header limit; both headers, and the primary data between them, must end inside it. Returns the
// extension's cards.
Cards check_headers(const std::string& head, std::uint64_t file_bytes, const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
  std::size_t at = 0;
  // Cards to END, printable ASCII only, the mandatory keywords first and in the standard's order
  // (cfitsio reads those by position).
  auto header = [&](const char* which, const std::vector<std::string>& leading) {
    Cards cards(source);
    for (std::size_t n = 0;; ++n) {
      if (at + 80 > head.size()) fail(std::string("the ") + which + " header has no END within " + std::to_string(healpix::kMaxHealpixHeaderBytes) + " bytes");
      const std::string card = head.substr(at, 80);
      at += 80;
      if (std::any_of(card.begin(), card.end(), [](char c) { return c < 0x20 || c > 0x7e; }))
        fail(std::string("the ") + which + " header's card " + std::to_string(n + 1) + " holds a byte that is not printable ASCII");
      const std::string key = trimmed(card.substr(0, 8).c_str());
      if (n < leading.size() && (key != leading[n] || card.compare(8, 2, "= ") != 0))
        fail(std::string("the ") + which + " header's card " + std::to_string(n + 1) + " is not '" + leading[n] + " = value'");
      if (key == "END") break;
      if (card.compare(8, 2, "= ") == 0) cards.add(key, card.substr(10));
    }
    at = (at + kFitsBlock - 1) / kFitsBlock * kFitsBlock;
    return cards;
  };
  if (head.compare(0, 9, "SIMPLE  =") != 0) fail("not a FITS file (no SIMPLE card)");
  // NAXIS read ahead, checked like every header integer: how many NAXISn cards must follow it.
  long long axes_claimed = 0;
  if (head.size() >= 240 && head.compare(160, 10, "NAXIS   = ") == 0) {
    Cards third(source);
    third.add("NAXIS", head.substr(170, 70));
    axes_claimed = third.integer("NAXIS", 0, healpix::kMaxFitsAxes).value_or(0);
  }
  std::vector<std::string> leading = {"SIMPLE", "BITPIX", "NAXIS"};
  for (long long k = 1; k <= std::min(axes_claimed, healpix::kMaxFitsAxes); ++k) leading.push_back("NAXIS" + std::to_string(k));
  const Cards primary = header("primary", leading);
  const long long limit = static_cast<long long>(file_bytes);
  const long long bits = primary.integer("BITPIX", -healpix::kMaxFitsBitpix, healpix::kMaxFitsBitpix).value_or(8), axes = primary.integer("NAXIS", 0, healpix::kMaxFitsAxes).value_or(0);
  if (axes != axes_claimed) fail("the primary header's NAXIS is malformed");
  long long data = axes > 0 ? std::abs(bits) / 8 : 0;
  for (long long k = 1; k <= axes; ++k) {
    data *= *primary.integer("NAXIS" + std::to_string(k), 0, limit);
    if (data > limit) fail("the primary data is larger than the file");
  }
  at += static_cast<std::size_t>((data + kFitsBlock - 1) / kFitsBlock * kFitsBlock);
  if (at >= head.size()) fail("no extension after the primary header within " + std::to_string(healpix::kMaxHealpixHeaderBytes) + " bytes");
  Cards table = header("extension", {"XTENSION", "BITPIX", "NAXIS", "NAXIS1", "NAXIS2", "PCOUNT", "GCOUNT", "TFIELDS"});
  if (table.text("XTENSION") != "BINTABLE") fail("the first extension is not a binary table");
  if (table.integer("BITPIX", -healpix::kMaxFitsBitpix, healpix::kMaxFitsBitpix) != 8 || table.integer("NAXIS", 0, healpix::kMaxFitsAxes) != 2 || table.integer("GCOUNT", 0, limit) != 1)
    fail("the table's BITPIX, NAXIS or GCOUNT is not 8, 2 and 1");
  const long long fields = *table.integer("TFIELDS", 1, healpix::kMaxFitsFields);
  for (long long k = 1; k <= fields; ++k)
    if (!table.text("TFORM" + std::to_string(k))) fail("no TFORM" + std::to_string(k) + " keyword");
  const long long width = *table.integer("NAXIS1", 0, limit), rows = *table.integer("NAXIS2", 0, limit);
  if (width > 0 && rows > limit / width) fail("the table is larger than the file");
  table.integer("PCOUNT", 0, limit);
  table.integer("THEAP", 0, limit);
  // The column keywords cfitsio parses on opening the table, in the forms the standard gives them.
  for (const std::string& key : table.keys()) {
    const std::string stem = key.substr(0, 5);
    if (stem == "TFORM" || stem == "TTYPE" || stem == "TUNIT" || stem == "TDISP" || key.rfind("TDIM", 0) == 0) table.text(key);
    else if (stem == "TNULL") table.integer(key, -kLargestInteger, kLargestInteger);
    else if (stem == "TSCAL" || stem == "TZERO") table.number(key);
  }
  return table;
}

class MapReader {
 public:
  MapReader(fitsfile* file, const Cards& cards, std::uint64_t file_bytes, const std::string& source)
      : file_(file), cards_(cards), file_bytes_(file_bytes), source_(source) {}

  HealpixMap read() {
    int hdu_type = 0;
    if (fits_movabs_hdu(file_, 2, &hdu_type, &status_)) fail("no extension after the primary header (" + fits_text(status_) + ")");
    if (hdu_type != BINARY_TBL) fail("the first extension is not a binary table");
    LONGLONG header_start = 0, data_start = 0, data_end = 0;
    check(fits_get_hduaddrll(file_, &header_start, &data_start, &data_end, &status_), "the table's header");
    if (static_cast<std::uint64_t>(data_start) > healpix::kMaxHealpixHeaderBytes)
      fail("headers of " + std::to_string(data_start) + " bytes, more than the limit of " + std::to_string(healpix::kMaxHealpixHeaderBytes));
    const LONGLONG padded_end = (data_end + kFitsBlock - 1) / kFitsBlock * kFitsBlock;
    if (static_cast<std::uint64_t>(data_end) > file_bytes_)
      fail("truncated: the table needs " + std::to_string(data_end) + " bytes, the file has " + std::to_string(file_bytes_));
    if (file_bytes_ > static_cast<std::uint64_t>(padded_end))
      fail(std::to_string(file_bytes_ - static_cast<std::uint64_t>(padded_end)) + " bytes after the map's table (a second extension is not read)");

    if (cards_.text("PIXTYPE").value_or("") != "HEALPIX") fail("PIXTYPE is not 'HEALPIX'");
    HealpixMap map;
    const std::string ordering = required(cards_.text("ORDERING"), "ORDERING");
    if (ordering == "RING") map.ordering = HealpixOrdering::kRing;
    else if (ordering == "NESTED" || ordering == "NEST") map.ordering = HealpixOrdering::kNested;
    else fail("ORDERING '" + excerpt(ordering) + "' is not RING or NESTED");
    map.nside = required(cards_.integer("NSIDE", 1, kMaxHealpixNside), "NSIDE");
    if (map.ordering == HealpixOrdering::kNested && !power_of_two(map.nside))
      fail("NSIDE " + std::to_string(map.nside) + " is not a power of two, as NESTED ordering needs");
    const std::int64_t pixels = healpix_pixels(map.nside);
    const std::string scheme = cards_.text("INDXSCHM").value_or("");
    if (!scheme.empty() && scheme != "IMPLICIT") fail("INDXSCHM '" + excerpt(scheme) + "' (a partial map) is not read: only IMPLICIT");

    int columns = 0, type = 0;
    LONGLONG rows = 0, repeat = 0, width = 0;
    check(fits_get_num_cols(file_, &columns, &status_), "its columns");
    check(fits_get_num_rowsll(file_, &rows, &status_), "its rows");
    if (columns < 1) fail("the table has no column");
    check(fits_get_coltypell(file_, 1, &type, &repeat, &width, &status_), "column 1");
    const bool integer = type == TBYTE || type == TSBYTE || type == TSHORT || type == TUSHORT || type == TLONG || type == TULONG || type == TLONGLONG;
    if (!integer && type != TFLOAT && type != TDOUBLE) fail("column 1 is not of a number type (FITS type code " + std::to_string(type) + ")");
    if (repeat < 1 || rows < 0 || rows > pixels || repeat * rows != pixels)
      fail("column 1 holds " + std::to_string(rows) + " rows of " + std::to_string(repeat) + " values, not 12 NSIDE^2 = " + std::to_string(pixels) +
           " (NSIDE " + std::to_string(map.nside) + ")");

    if (cards_.integer("FIRSTPIX", -kLargestInteger, kLargestInteger).value_or(0) != 0) fail("FIRSTPIX is not 0");
    const std::int64_t last = cards_.integer("LASTPIX", -kLargestInteger, kLargestInteger).value_or(pixels - 1);
    if (last != pixels - 1) fail("LASTPIX " + std::to_string(last) + " is not 12 NSIDE^2 - 1 = " + std::to_string(pixels - 1));

    map.pixels.resize(static_cast<std::size_t>(pixels));
    std::vector<char> nulls(integer ? static_cast<std::size_t>(kPixelsPerCall) : 0);
    for (LONGLONG first = 0; first < pixels; first += kPixelsPerCall) {
      throw_if_interrupted();
      const LONGLONG count = std::min<LONGLONG>(kPixelsPerCall, pixels - first);
      double* out = map.pixels.data() + first;
      int any_null = 0;
      if (integer) {
        check(fits_read_colnull(file_, TDOUBLE, 1, first / repeat + 1, first % repeat + 1, count, out, nulls.data(), &any_null, &status_), "the pixels");
        if (any_null)
          fail("pixel " + std::to_string(first + (std::find(nulls.begin(), nulls.begin() + count, 1) - nulls.begin())) + " is null (TNULL)");
      } else {
        double no_check = 0;
        check(fits_read_col(file_, TDOUBLE, 1, first / repeat + 1, first % repeat + 1, count, &no_check, out, &any_null, &status_), "the pixels");
      }
      for (LONGLONG k = 0; k < count; ++k) {
        if (!std::isfinite(out[k])) fail("pixel " + std::to_string(first + k) + " is " + (std::isnan(out[k]) ? "NaN" : "infinite"));
        if (is_unseen(out[k]) && map.unseen++ == 0) map.first_unseen = first + k;
      }
    }
    return map;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(source_ + ": " + what); }
  void check(int status, const char* reading) {
    if (status) fail(std::string("FITS error reading ") + reading + ": " + fits_text(status));
  }
  template <class T>
  T required(const std::optional<T>& value, const char* key) const {
    if (!value) fail(std::string("no ") + key + " keyword");
    return *value;
  }

  fitsfile* file_;
  const Cards& cards_;
  std::uint64_t file_bytes_;
  const std::string& source_;
  int status_ = 0;
};

HealpixMap read_opened(fitsfile* raw, int status, const Cards& cards, std::uint64_t bytes, const std::string& source) {
  if (status) {
    if (raw) FitsCloser()(raw);
    throw InputError(source + ": not a FITS file (" + fits_text(status) + ")");
  }
  FitsFile file(raw);
  return MapReader(file.get(), cards, bytes, source).read();
}

void check_map(const HealpixMap& map) {
  if (map.nside < 1 || map.nside > kMaxHealpixNside) throw std::invalid_argument("HEALPix Nside " + std::to_string(map.nside) + " is outside 1.." + std::to_string(kMaxHealpixNside));
  if (map.ordering == HealpixOrdering::kNested && !power_of_two(map.nside))
    throw std::invalid_argument("HEALPix Nside " + std::to_string(map.nside) + " is not a power of two, as NESTED ordering needs");
  if (static_cast<std::int64_t>(map.pixels.size()) != healpix_pixels(map.nside))
    throw std::invalid_argument(std::to_string(map.pixels.size()) + " pixels are not 12 Nside^2 (Nside " + std::to_string(map.nside) + ")");
}

}  // namespace

bool is_unseen(double value) { return std::abs(value - kHealpixUnseen) <= zhf::tolerance::kHealpixUnseenRelative * std::abs(kHealpixUnseen); }

std::int64_t healpix_pixels(std::int64_t nside) { return 12 * nside * nside; }

HealpixMap read_healpix_map(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) throw InputError(path + ": cannot be read (missing or not accessible)");
  if (S_ISREG(st.st_mode) && st.st_size == 0) throw InputError(path + ": empty, not a FITS file");
  if (!S_ISREG(st.st_mode)) return parse_healpix_map(runtime::read_file(path, healpix::kMaxHealpixHeaderBytes + healpix_pixels(kMaxHealpixNside) * 8), path);
  std::string head(std::min<std::size_t>(static_cast<std::size_t>(st.st_size), healpix::kMaxHealpixHeaderBytes), '\0');
  std::ifstream in(path, std::ios::binary);
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) throw InputError(path + ": cannot be read");
  const Cards cards = check_headers(head, static_cast<std::uint64_t>(st.st_size), path);
  fitsfile* raw = nullptr;
  int status = 0;
  fits_open_diskfile(&raw, path.c_str(), READONLY, &status);  // the name taken as is: no cfitsio filename syntax
  return read_opened(raw, status, cards, static_cast<std::uint64_t>(st.st_size), path);
}

HealpixMap parse_healpix_map(const std::string& bytes, const std::string& source) {
  if (bytes.empty()) throw InputError(source + ": empty, not a FITS file");
  const Cards cards = check_headers(bytes.substr(0, healpix::kMaxHealpixHeaderBytes), bytes.size(), source);
  void* buffer = const_cast<char*>(bytes.data());  // read only: cfitsio neither writes nor grows it
  std::size_t size = bytes.size();
  fitsfile* raw = nullptr;
  int status = 0;
  fits_open_memfile(&raw, "memory", READONLY, &buffer, &size, 0, nullptr, &status);
  return read_opened(raw, status, cards, bytes.size(), source);
}

std::string encode_healpix_map(const HealpixMap& map) {
  check_map(map);
  const LONGLONG pixels = healpix_pixels(map.nside);
  const LONGLONG per_row = pixels % kValuesPerRow == 0 ? kValuesPerRow : 1;
  // cfitsio grows the buffer with realloc; closing a memory file leaves the buffer to its owner.
  struct MemoryFits {
    std::size_t size = kFitsBlock;
    void* buffer = std::malloc(kFitsBlock);
    fitsfile* file = nullptr;
    ~MemoryFits() {
      if (file) FitsCloser()(file);
      std::free(buffer);
    }
  } fits;
  if (!fits.buffer) throw std::bad_alloc();
  int status = 0;
  auto check = [&](const char* what) {
    if (status) throw std::runtime_error(std::string("writing a HEALPix map: ") + what + ": " + fits_text(status));
  };
  fits_create_memfile(&fits.file, &fits.buffer, &fits.size, static_cast<std::size_t>(kFitsBlock) * 64, std::realloc, &status);
  check("creating the file");
  fitsfile* f = fits.file;
  fits_create_img(f, BYTE_IMG, 0, nullptr, &status);
  char type[] = "SIGNAL", unit[] = "";
  std::string form = std::to_string(per_row) + "D";
  char* types[] = {type};
  char* forms[] = {form.data()};
  char* units[] = {unit};
  fits_create_tbl(f, BINARY_TBL, pixels / per_row, 1, types, forms, units, nullptr, &status);
  char healpix[] = "HEALPIX", ring[] = "RING", nested[] = "NESTED", implicit[] = "IMPLICIT", fullsky[] = "FULLSKY";
  LONGLONG nside = map.nside, first = 0, last = pixels - 1;
  fits_write_key(f, TSTRING, "PIXTYPE", healpix, "HEALPIX pixelisation", &status);
  fits_write_key(f, TSTRING, "ORDERING", map.ordering == HealpixOrdering::kRing ? ring : nested, "Pixel ordering scheme, RING or NESTED", &status);
  fits_write_key(f, TLONGLONG, "NSIDE", &nside, "Resolution parameter of HEALPix", &status);
  fits_write_key(f, TLONGLONG, "FIRSTPIX", &first, "First pixel # (0 based)", &status);
  fits_write_key(f, TLONGLONG, "LASTPIX", &last, "Last pixel # (0 based)", &status);
  fits_write_key(f, TSTRING, "INDXSCHM", implicit, "Indexing: IMPLICIT or EXPLICIT", &status);
  fits_write_key(f, TSTRING, "OBJECT", fullsky, "Sky coverage", &status);
  fits_write_comment(f, "Written by zhf (values as given; zhf's SH are real, orthonormal, without Condon-Shortley phase).", &status);
  check("the table's header");
  for (LONGLONG at = 0; at < pixels; at += kPixelsPerCall) {
    throw_if_interrupted();
    const LONGLONG count = std::min<LONGLONG>(kPixelsPerCall, pixels - at);
    fits_write_col(f, TDOUBLE, 1, at / per_row + 1, at % per_row + 1, count, const_cast<double*>(map.pixels.data() + at), &status);
    check("the pixels");
  }
  LONGLONG header_start = 0, data_start = 0, data_end = 0;
  fits_flush_file(f, &status);
  fits_get_hduaddrll(f, &header_start, &data_start, &data_end, &status);
  fits_close_file(f, &status);
  fits.file = nullptr;
  check("closing the file");
  const LONGLONG length = (data_end + kFitsBlock - 1) / kFitsBlock * kFitsBlock;
  if (length > static_cast<LONGLONG>(fits.size)) throw std::runtime_error("writing a HEALPix map: cfitsio's buffer is shorter than the file");
  return std::string(static_cast<const char*>(fits.buffer), static_cast<std::size_t>(length));
}

void write_healpix_map(const std::string& path, const HealpixMap& map) {
  io::PendingFile out(path);
  out.write(encode_healpix_map(map));
  out.commit();
}

}  // namespace zhf::healpix
