/*
 * pcprof: a QEMU TCG plugin that counts how often each guest instruction runs
 * inside the bench firmware's measured regions (bench/mcu), for bench/profile.sh
 * and bench/footprint.sh.
 *
 * A region is what the guest executes from a call of its empty marker function
 * `bench_start` to the next call of `bench_stop` (the markers' own instructions
 * are not counted). Every instruction gets an inline counter (no callback on
 * the hot path); at each marker the plugin takes a snapshot of the counters, so
 * a region's counts are the differences.
 *
 * Arguments (-plugin pcprof.so,arg=value,...):
 *   region=N|all  the region(s) whose instructions go to the output: N counts
 *                 from 0 in the order the guest runs them, N+M+... several of
 *                 them together (default all)
 *   out=FILE      where to write (default stderr)
 *   start=ADDR    address of bench_start (hex); stop=ADDR of bench_stop.
 *                 Without them the markers are found by their ELF symbol names
 *                 (QEMU's symbol lookup of the -kernel ELF).
 *
 * Output: lines "# region I insns N" for every region the guest ran, then
 * "# selected REGION insns N" (their sum over the selected regions), then "ADDR SIZE COUNT" (hex address, bytes, decimal
 * count) for each instruction executed at least once in the selected regions.
 *
 * Self-contained: it declares the few plugin API entry points it uses rather
 * than including qemu-plugin.h (Debian ships no plugin header). QEMU 7.2 to 8.2
 * have plugin API 1 (inline ops on a plain pointer); 9.0 and later dropped
 * those for per-vCPU "scoreboards" and refuse API 1 plugins. Both sets are
 * declared weak and the plugin picks the one this QEMU exports at load time.
 * Build: gcc -O2 -shared -fPIC -o pcprof.so pcprof.c
 */
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- The part of QEMU's plugin API this uses. */
#define EXPORT __attribute__((visibility("default")))
#define WEAK __attribute__((weak))
typedef uint64_t plugin_id;
struct qemu_info_t; /* not looked at */
struct qemu_plugin_tb;
struct qemu_plugin_insn;
struct qemu_plugin_scoreboard;
enum { CB_NO_REGS = 0 };    /* enum qemu_plugin_cb_flags */
enum { INLINE_ADD_U64 = 0 }; /* enum qemu_plugin_op */
typedef struct {
    struct qemu_plugin_scoreboard *score;
    size_t offset;
} plugin_u64; /* qemu_plugin_u64, API 2+ */
typedef void (*tb_trans_cb)(plugin_id, struct qemu_plugin_tb *);
typedef void (*vcpu_udata_cb)(unsigned int vcpu, void *udata);
typedef void (*udata_cb)(plugin_id, void *udata);

void qemu_plugin_register_vcpu_tb_trans_cb(plugin_id, tb_trans_cb);
void qemu_plugin_register_atexit_cb(plugin_id, udata_cb, void *);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *, vcpu_udata_cb, int flags, void *);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *, size_t);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *);
size_t qemu_plugin_insn_size(const struct qemu_plugin_insn *);
const char *qemu_plugin_insn_symbol(const struct qemu_plugin_insn *);
/* API 1 only (QEMU 7.x, 8.x). */
WEAK void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *, int op, void *ptr, uint64_t imm);
/* API 2 and later (QEMU 9.0 on). */
WEAK struct qemu_plugin_scoreboard *qemu_plugin_scoreboard_new(size_t element_size);
WEAK void *qemu_plugin_scoreboard_find(struct qemu_plugin_scoreboard *, unsigned int vcpu);
WEAK void qemu_plugin_register_vcpu_insn_exec_inline_per_vcpu(struct qemu_plugin_insn *, int op, plugin_u64 entry,
                                                              uint64_t imm);

EXPORT int qemu_plugin_version = 1;

/* Runs when QEMU opens the plugin, before it reads qemu_plugin_version. */
__attribute__((constructor)) static void pick_api(void)
{
    if (qemu_plugin_scoreboard_new && qemu_plugin_register_vcpu_insn_exec_inline_per_vcpu)
        qemu_plugin_version = 2;
}

/* ---- Counters: in chunks that never move (the translated code holds their
 * addresses), one slot per distinct instruction address. */
#define CHUNK 4096
struct chunk {
    uint64_t *plain;                     /* API 1 */
    struct qemu_plugin_scoreboard *board; /* API 2+: one element of CHUNK counters */
};
static struct chunk *chunks;
static size_t n_chunks;

struct insn {
    uint64_t addr;
    uint32_t size;
    uint32_t slot; /* chunk * CHUNK + index */
    uint64_t base; /* its counter when the current region began */
    uint64_t hits; /* executions in the selected regions */
};
static struct insn *insns;
static size_t n_insns, cap_insns;

/* Open-addressing table: instruction address -> index in insns + 1 (0 = empty). */
static uint32_t *table;
static size_t table_size; /* a power of two */

static uint64_t *counter(uint32_t slot)
{
    struct chunk *c = &chunks[slot / CHUNK];
    uint64_t *v = c->plain ? c->plain : qemu_plugin_scoreboard_find(c->board, 0);
    return &v[slot % CHUNK];
}

static size_t hash(uint64_t a) { return (size_t)((a >> 1) * 0x9E3779B97F4A7C15ull >> 20); }

static void grow_table(void)
{
    size_t size = table_size ? table_size * 2 : 1 << 14;
    uint32_t *t = calloc(size, sizeof *t);
    if (!t) abort();
    for (size_t i = 0; i < n_insns; i++) {
        size_t h = hash(insns[i].addr) & (size - 1);
        while (t[h]) h = (h + 1) & (size - 1);
        t[h] = (uint32_t)i + 1;
    }
    free(table);
    table = t;
    table_size = size;
}

static struct insn *lookup(uint64_t addr, uint32_t size)
{
    if (2 * (n_insns + 1) > table_size) grow_table();
    size_t h = hash(addr) & (table_size - 1);
    while (table[h]) {
        struct insn *r = &insns[table[h] - 1];
        if (r->addr == addr) return r;
        h = (h + 1) & (table_size - 1);
    }
    if (n_insns % CHUNK == 0) {
        chunks = realloc(chunks, (n_chunks + 1) * sizeof *chunks);
        if (!chunks) abort();
        struct chunk *c = &chunks[n_chunks++];
        c->plain = NULL;
        c->board = NULL;
        if (qemu_plugin_version == 1) {
            c->plain = calloc(CHUNK, sizeof(uint64_t));
            if (!c->plain) abort();
        } else {
            c->board = qemu_plugin_scoreboard_new(CHUNK * sizeof(uint64_t));
        }
    }
    if (n_insns == cap_insns) {
        cap_insns = cap_insns ? cap_insns * 2 : 4096;
        insns = realloc(insns, cap_insns * sizeof *insns);
        if (!insns) abort();
    }
    struct insn *r = &insns[n_insns];
    r->addr = addr;
    r->size = size;
    r->slot = (uint32_t)n_insns;
    /* A new instruction inside a region: its counter is 0 (never ran). */
    r->base = *counter(r->slot);
    r->hits = 0;
    table[h] = (uint32_t)++n_insns;
    return r;
}

/* ---- Regions. */
#define MAX_REGIONS 1024
static bool want_all = true;
static bool want[MAX_REGIONS];
static const char *want_arg = "all";
static uint64_t start_addr, stop_addr;
static bool by_address;
static bool inside;
static long region;     /* index of the next region to start */
static uint64_t region_base;
static FILE *out;
static uint64_t region_insns[MAX_REGIONS];
static uint64_t selected_insns;

static uint64_t total(void)
{
    uint64_t t = 0;
    for (size_t i = 0; i < n_insns; i++) t += *counter(insns[i].slot);
    return t;
}

static void on_start(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (inside) return; /* nested start: the outer region goes on */
    inside = true;
    region_base = 0;
    for (size_t i = 0; i < n_insns; i++) region_base += insns[i].base = *counter(insns[i].slot);
}

static void on_stop(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (!inside) return;
    inside = false;
    uint64_t n = total() - region_base;
    if (region < MAX_REGIONS) region_insns[region] = n;
    if (want_all || (region < MAX_REGIONS && want[region])) {
        selected_insns += n;
        for (size_t i = 0; i < n_insns; i++) insns[i].hits += *counter(insns[i].slot) - insns[i].base;
    }
    region++;
}

static void on_translate(plugin_id id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *in = qemu_plugin_tb_get_insn(tb, i);
        uint64_t addr = qemu_plugin_insn_vaddr(in);
        bool is_start, is_stop;
        if (by_address) {
            is_start = addr == start_addr;
            is_stop = addr == stop_addr;
        } else {
            const char *sym = qemu_plugin_insn_symbol(in);
            is_start = sym && !strcmp(sym, "bench_start");
            is_stop = sym && !strcmp(sym, "bench_stop");
        }
        if (is_start || is_stop) {
            qemu_plugin_register_vcpu_insn_exec_cb(in, is_start ? on_start : on_stop, CB_NO_REGS, NULL);
            continue;
        }
        struct insn *r = lookup(addr, (uint32_t)qemu_plugin_insn_size(in));
        struct chunk *c = &chunks[r->slot / CHUNK];
        if (c->plain) {
            qemu_plugin_register_vcpu_insn_exec_inline(in, INLINE_ADD_U64, &c->plain[r->slot % CHUNK], 1);
        } else {
            plugin_u64 entry = {c->board, (r->slot % CHUNK) * sizeof(uint64_t)};
            qemu_plugin_register_vcpu_insn_exec_inline_per_vcpu(in, INLINE_ADD_U64, entry, 1);
        }
    }
}

static void at_exit(plugin_id id, void *udata)
{
    (void)id;
    (void)udata;
    FILE *f = out ? out : stderr;
    if (inside) {
        fprintf(f, "# region %ld did not stop: counted up to the exit\n", region);
        on_stop(0, NULL);
    }
    for (long i = 0; i < region && i < MAX_REGIONS; i++)
        fprintf(f, "# region %ld insns %" PRIu64 "\n", i, region_insns[i]);
    fprintf(f, "# selected %s insns %" PRIu64 "\n", want_arg, selected_insns);
    for (size_t i = 0; i < n_insns; i++)
        if (insns[i].hits) fprintf(f, "0x%08" PRIx64 " %" PRIu32 " %" PRIu64 "\n", insns[i].addr, insns[i].size, insns[i].hits);
    fflush(f);
}

static bool arg(const char *a, const char *key, const char **value)
{
    size_t n = strlen(key);
    if (strncmp(a, key, n) || a[n] != '=') return false;
    *value = a + n + 1;
    return true;
}

static bool number(const char *s, int base, uint64_t *v)
{
    char *end;
    if (!*s) return false;
    *v = strtoull(s, &end, base);
    return *end == 0;
}

/* "N" or "N+M+...": sets want[]. */
static bool regions(const char *s)
{
    memset(want, 0, sizeof want);
    for (;;) {
        char *end;
        if (*s < '0' || *s > '9') return false;
        unsigned long n = strtoul(s, &end, 10);
        if (n >= MAX_REGIONS) return false;
        want[n] = true;
        if (!*end) return true;
        if (*end != '+') return false;
        s = end + 1;
    }
}

EXPORT int qemu_plugin_install(plugin_id id, const struct qemu_info_t *info, int argc, char **argv)
{
    (void)info;
    const char *v;
    bool have_start = false, have_stop = false;
    if (qemu_plugin_version == 1 && !qemu_plugin_register_vcpu_insn_exec_inline) {
        fprintf(stderr, "pcprof: this QEMU has neither plugin API 1 nor 2 inline counters\n");
        return -1;
    }
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (arg(a, "region", &v)) {
            want_arg = v;
            want_all = !strcmp(v, "all");
            if (!want_all && !regions(v)) goto bad;
        } else if (arg(a, "out", &v)) {
            out = fopen(v, "w");
            if (!out) {
                fprintf(stderr, "pcprof: cannot write %s\n", v);
                return -1;
            }
        } else if (arg(a, "start", &v)) {
            if (!number(v, 16, &start_addr)) goto bad;
            have_start = true;
        } else if (arg(a, "stop", &v)) {
            if (!number(v, 16, &stop_addr)) goto bad;
            have_stop = true;
        } else {
            goto bad;
        }
        continue;
    bad:
        fprintf(stderr, "pcprof: bad argument %s (region=N|all, out=FILE, start=ADDR, stop=ADDR)\n", a);
        return -1;
    }
    if (have_start != have_stop) {
        fprintf(stderr, "pcprof: give both start= and stop=, or neither\n");
        return -1;
    }
    by_address = have_start;
    /* Thumb: a function symbol's address has bit 0 set, its code does not. */
    start_addr &= ~(uint64_t)1;
    stop_addr &= ~(uint64_t)1;
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, at_exit, NULL);
    return 0;
}
