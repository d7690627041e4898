/* sbl_dataset.c - scene directory loader (see sbl_dataset.h), with a small
 * JSON reader of its own so the tools need nothing beyond OpenEXR. */
#include "sbl_dataset.h"
#include "sbl_exr.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void sbl__ds_err(char *err, int err_size, const char *fmt, ...)
{
    va_list ap;
    if (!err || err_size <= 0) return;
    va_start(ap, fmt);
    vsnprintf(err, (size_t)err_size, fmt, ap);
    va_end(ap);
}

/* ---------------------------------------------------------------- JSON -- */

enum { SBL_J_NULL, SBL_J_BOOL, SBL_J_NUM, SBL_J_STR, SBL_J_ARR, SBL_J_OBJ };

typedef struct sbl__jv {
    int type;
    double num;             /* NUM, BOOL (0/1) */
    char *str;              /* STR */
    int count;              /* ARR, OBJ */
    struct sbl__jv *items;  /* ARR, OBJ values */
    char **keys;            /* OBJ keys */
} sbl__jv;

typedef struct sbl__jp {
    const char *s, *p, *end;
    char *err;
    int err_size;
    int failed;
} sbl__jp;

/* Deep enough for any camera file; bounds recursion on hostile input. */
#define SBL__JSON_MAX_DEPTH 64

static void sbl__jv_free(sbl__jv *v)
{
    int i;
    if (!v) return;
    if (v->type == SBL_J_STR) free(v->str);
    if (v->type == SBL_J_ARR || v->type == SBL_J_OBJ) {
        for (i = 0; i < v->count; ++i) {
            sbl__jv_free(&v->items[i]);
            if (v->keys) free(v->keys[i]);
        }
        free(v->items);
        free(v->keys);
    }
    memset(v, 0, sizeof(*v));
}

static int sbl__jp_fail(sbl__jp *jp, const char *what)
{
    if (!jp->failed) {
        int line = 1, col = 1;
        const char *q;
        for (q = jp->s; q < jp->p && q < jp->end; ++q) {
            if (*q == '\n') { ++line; col = 1; } else ++col;
        }
        sbl__ds_err(jp->err, jp->err_size, "line %d col %d: %s", line, col, what);
        jp->failed = 1;
    }
    return -1;
}

static void sbl__jp_ws(sbl__jp *jp)
{
    while (jp->p < jp->end && (*jp->p == ' ' || *jp->p == '\t' || *jp->p == '\n' || *jp->p == '\r'))
        ++jp->p;
}

static int sbl__jp_hex4(sbl__jp *jp, unsigned *out)
{
    int i;
    unsigned v = 0;
    if (jp->end - jp->p < 4) return sbl__jp_fail(jp, "truncated \\u escape");
    for (i = 0; i < 4; ++i) {
        char c = jp->p[i];
        v <<= 4;
        if (c >= '0' && c <= '9') v |= (unsigned)(c - '0');
        else if (c >= 'a' && c <= 'f') v |= (unsigned)(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F') v |= (unsigned)(c - 'A' + 10);
        else return sbl__jp_fail(jp, "bad \\u escape");
    }
    jp->p += 4;
    *out = v;
    return 0;
}

/* On entry jp->p is at the opening quote. Result is malloc'ed, NUL-terminated
 * (escapes decoded; \u0000 is kept as a byte, which only truncates the key). */
static int sbl__jp_string(sbl__jp *jp, char **out)
{
    const char *q;
    char *buf, *w;
    size_t cap = 1;
    *out = NULL;
    ++jp->p;
    /* Decoded text is never longer than the source: size from the source. */
    for (q = jp->p; q < jp->end && *q != '"'; ++q) {
        if (*q == '\\' && q + 1 < jp->end) ++q;
        ++cap;
    }
    if (q >= jp->end) return sbl__jp_fail(jp, "unterminated string");
    buf = (char *)malloc(cap * 2 + 4);
    if (!buf) return sbl__jp_fail(jp, "out of memory");
    w = buf;
    while (jp->p < jp->end && *jp->p != '"') {
        unsigned char c = (unsigned char)*jp->p;
        if (c < 0x20) { free(buf); return sbl__jp_fail(jp, "control character in string"); }
        if (c != '\\') { *w++ = (char)c; ++jp->p; continue; }
        ++jp->p;
        if (jp->p >= jp->end) { free(buf); return sbl__jp_fail(jp, "unterminated string"); }
        c = (unsigned char)*jp->p++;
        switch (c) {
        case '"': *w++ = '"'; break;
        case '\\': *w++ = '\\'; break;
        case '/': *w++ = '/'; break;
        case 'b': *w++ = '\b'; break;
        case 'f': *w++ = '\f'; break;
        case 'n': *w++ = '\n'; break;
        case 'r': *w++ = '\r'; break;
        case 't': *w++ = '\t'; break;
        case 'u': {
            unsigned cp, lo;
            if (sbl__jp_hex4(jp, &cp)) { free(buf); return -1; }
            if (cp >= 0xD800 && cp <= 0xDBFF) {
                if (jp->end - jp->p >= 6 && jp->p[0] == '\\' && jp->p[1] == 'u') {
                    jp->p += 2;
                    if (sbl__jp_hex4(jp, &lo)) { free(buf); return -1; }
                    if (lo >= 0xDC00 && lo <= 0xDFFF) cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    else cp = 0xFFFD;
                } else {
                    cp = 0xFFFD;
                }
            } else if (cp >= 0xDC00 && cp <= 0xDFFF) {
                cp = 0xFFFD;
            }
            /* UTF-8 (at most 4 bytes from a 6 or 12 byte escape: fits). */
            if (cp < 0x80) *w++ = (char)cp;
            else if (cp < 0x800) { *w++ = (char)(0xC0 | (cp >> 6)); *w++ = (char)(0x80 | (cp & 0x3F)); }
            else if (cp < 0x10000) {
                *w++ = (char)(0xE0 | (cp >> 12)); *w++ = (char)(0x80 | ((cp >> 6) & 0x3F));
                *w++ = (char)(0x80 | (cp & 0x3F));
            } else {
                *w++ = (char)(0xF0 | (cp >> 18)); *w++ = (char)(0x80 | ((cp >> 12) & 0x3F));
                *w++ = (char)(0x80 | ((cp >> 6) & 0x3F)); *w++ = (char)(0x80 | (cp & 0x3F));
            }
            break;
        }
        default:
            free(buf);
            return sbl__jp_fail(jp, "bad escape in string");
        }
    }
    ++jp->p; /* closing quote (existence checked above) */
    *w = '\0';
    *out = buf;
    return 0;
}

/* JSON grammar checked by hand, then strtod (which would accept more:
 * hex, inf, nan). strtod reads the C locale's decimal point. */
static int sbl__jp_number(sbl__jp *jp, double *out)
{
    const char *q = jp->p;
    char tmp[64];
    size_t n;
    if (q < jp->end && *q == '-') ++q;
    if (q >= jp->end || *q < '0' || *q > '9') return sbl__jp_fail(jp, "bad number");
    if (*q == '0') ++q;
    else while (q < jp->end && *q >= '0' && *q <= '9') ++q;
    if (q < jp->end && *q == '.') {
        ++q;
        if (q >= jp->end || *q < '0' || *q > '9') return sbl__jp_fail(jp, "bad number");
        while (q < jp->end && *q >= '0' && *q <= '9') ++q;
    }
    if (q < jp->end && (*q == 'e' || *q == 'E')) {
        ++q;
        if (q < jp->end && (*q == '+' || *q == '-')) ++q;
        if (q >= jp->end || *q < '0' || *q > '9') return sbl__jp_fail(jp, "bad number");
        while (q < jp->end && *q >= '0' && *q <= '9') ++q;
    }
    n = (size_t)(q - jp->p);
    if (n >= sizeof(tmp)) return sbl__jp_fail(jp, "number too long");
    memcpy(tmp, jp->p, n); /* copy: the buffer need not be NUL-terminated here */
    tmp[n] = '\0';
    *out = strtod(tmp, NULL);
    jp->p = q;
    return 0;
}

static int sbl__jp_value(sbl__jp *jp, sbl__jv *v, int depth);

/* Append one element; items/keys grow geometrically. */
static int sbl__jv_push(sbl__jp *jp, sbl__jv *v, int *cap, sbl__jv *item, char *key)
{
    if (v->count == *cap) {
        int nc = *cap ? *cap * 2 : 4;
        sbl__jv *ni;
        if (nc > (1 << 26)) return sbl__jp_fail(jp, "container too large");
        ni = (sbl__jv *)realloc(v->items, (size_t)nc * sizeof(sbl__jv));
        if (!ni) return sbl__jp_fail(jp, "out of memory");
        v->items = ni;
        if (v->type == SBL_J_OBJ) {
            char **nk = (char **)realloc(v->keys, (size_t)nc * sizeof(char *));
            if (!nk) return sbl__jp_fail(jp, "out of memory");
            v->keys = nk;
        }
        *cap = nc;
    }
    v->items[v->count] = *item;
    if (v->type == SBL_J_OBJ) v->keys[v->count] = key;
    ++v->count;
    return 0;
}

static int sbl__jp_container(sbl__jp *jp, sbl__jv *v, int depth, int is_obj)
{
    int cap = 0;
    char close = is_obj ? '}' : ']';
    v->type = is_obj ? SBL_J_OBJ : SBL_J_ARR;
    ++jp->p;
    sbl__jp_ws(jp);
    if (jp->p < jp->end && *jp->p == close) { ++jp->p; return 0; }
    for (;;) {
        sbl__jv item;
        char *key = NULL;
        memset(&item, 0, sizeof(item));
        sbl__jp_ws(jp);
        if (is_obj) {
            if (jp->p >= jp->end || *jp->p != '"') return sbl__jp_fail(jp, "expected object key");
            if (sbl__jp_string(jp, &key)) return -1;
            sbl__jp_ws(jp);
            if (jp->p >= jp->end || *jp->p != ':') { free(key); return sbl__jp_fail(jp, "expected ':'"); }
            ++jp->p;
        }
        if (sbl__jp_value(jp, &item, depth + 1)) { free(key); sbl__jv_free(&item); return -1; }
        if (sbl__jv_push(jp, v, &cap, &item, key)) { free(key); sbl__jv_free(&item); return -1; }
        sbl__jp_ws(jp);
        if (jp->p >= jp->end) return sbl__jp_fail(jp, is_obj ? "unterminated object" : "unterminated array");
        if (*jp->p == ',') { ++jp->p; continue; }
        if (*jp->p == close) { ++jp->p; return 0; }
        return sbl__jp_fail(jp, is_obj ? "expected ',' or '}'" : "expected ',' or ']'");
    }
}

static int sbl__jp_lit(sbl__jp *jp, const char *lit)
{
    size_t n = strlen(lit);
    if ((size_t)(jp->end - jp->p) < n || memcmp(jp->p, lit, n) != 0) return sbl__jp_fail(jp, "unexpected token");
    jp->p += n;
    return 0;
}

static int sbl__jp_value(sbl__jp *jp, sbl__jv *v, int depth)
{
    memset(v, 0, sizeof(*v));
    if (depth > SBL__JSON_MAX_DEPTH) return sbl__jp_fail(jp, "nested too deeply");
    sbl__jp_ws(jp);
    if (jp->p >= jp->end) return sbl__jp_fail(jp, "unexpected end of input");
    switch (*jp->p) {
    case '{': return sbl__jp_container(jp, v, depth, 1);
    case '[': return sbl__jp_container(jp, v, depth, 0);
    case '"': v->type = SBL_J_STR; return sbl__jp_string(jp, &v->str);
    case 't': v->type = SBL_J_BOOL; v->num = 1; return sbl__jp_lit(jp, "true");
    case 'f': v->type = SBL_J_BOOL; v->num = 0; return sbl__jp_lit(jp, "false");
    case 'n': v->type = SBL_J_NULL; return sbl__jp_lit(jp, "null");
    /* Python's json.dump writes these for non-finite floats: accept them. */
    case 'N': v->type = SBL_J_NUM; v->num = strtod("nan", NULL); return sbl__jp_lit(jp, "NaN");
    case 'I': v->type = SBL_J_NUM; v->num = strtod("inf", NULL); return sbl__jp_lit(jp, "Infinity");
    default:
        if (*jp->p == '-' && jp->end - jp->p >= 9 && memcmp(jp->p, "-Infinity", 9) == 0) {
            jp->p += 9;
            v->type = SBL_J_NUM;
            v->num = -strtod("inf", NULL);
            return 0;
        }
        v->type = SBL_J_NUM;
        return sbl__jp_number(jp, &v->num);
    }
}

static int sbl__json_parse(const char *text, size_t len, sbl__jv *root, char *err, int err_size)
{
    sbl__jp jp;
    jp.s = jp.p = text;
    jp.end = text + len;
    jp.err = err;
    jp.err_size = err_size;
    jp.failed = 0;
    if (sbl__jp_value(&jp, root, 0)) { sbl__jv_free(root); return -1; }
    sbl__jp_ws(&jp);
    if (jp.p != jp.end) { sbl__jv_free(root); return sbl__jp_fail(&jp, "trailing characters"); }
    return 0;
}

static const sbl__jv *sbl__jv_get(const sbl__jv *obj, const char *key)
{
    int i;
    if (!obj || obj->type != SBL_J_OBJ) return NULL;
    for (i = 0; i < obj->count; ++i)
        if (strcmp(obj->keys[i], key) == 0) return &obj->items[i];
    return NULL;
}

static const sbl__jv *sbl__jv_at(const sbl__jv *arr, int i)
{
    if (!arr || arr->type != SBL_J_ARR || i < 0 || i >= arr->count) return NULL;
    return &arr->items[i];
}

/* Integer in [lo, hi]; 0 on success. */
static int sbl__jv_int(const sbl__jv *v, int lo, int hi, int *out)
{
    if (!v || v->type != SBL_J_NUM || !(v->num >= lo && v->num <= hi) || v->num != (double)(int)v->num) return -1;
    *out = (int)v->num;
    return 0;
}

/* 4x4 matrix as 4 rows of 4 numbers, or a flat list of 16. */
static int sbl__jv_mat4(const sbl__jv *v, float m[16])
{
    int r, c;
    if (!v || v->type != SBL_J_ARR) return -1;
    if (v->count == 16) {
        for (r = 0; r < 16; ++r) {
            if (v->items[r].type != SBL_J_NUM) return -1;
            m[r] = (float)v->items[r].num;
        }
        return 0;
    }
    if (v->count != 4) return -1;
    for (r = 0; r < 4; ++r) {
        const sbl__jv *row = &v->items[r];
        if (row->type != SBL_J_ARR || row->count != 4) return -1;
        for (c = 0; c < 4; ++c) {
            if (row->items[c].type != SBL_J_NUM) return -1;
            m[4 * r + c] = (float)row->items[c].num;
        }
    }
    return 0;
}

static char *sbl__read_file(const char *path, size_t max_size, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t cap = 0, n = 0;
    if (!f) return NULL;
    for (;;) {
        size_t got;
        if (n + 4096 + 1 > cap) {
            size_t nc = cap ? cap * 2 : 65536;
            char *nb;
            if (nc > max_size + 4096 + 1) nc = max_size + 4096 + 1;
            if (nc <= cap) { free(buf); fclose(f); return NULL; } /* too large */
            nb = (char *)realloc(buf, nc);
            if (!nb) { free(buf); fclose(f); return NULL; }
            buf = nb;
            cap = nc;
        }
        got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0) break;
    }
    if (ferror(f) || n > max_size) { free(buf); fclose(f); return NULL; }
    fclose(f);
    buf[n] = '\0';
    *len = n;
    return buf;
}

static int sbl__load_json(const char *path, sbl__jv *root, char *err, int err_size)
{
    size_t len = 0;
    char *text = sbl__read_file(path, (size_t)256 << 20, &len);
    char msg[256];
    if (!text) {
        sbl__ds_err(err, err_size, "%s: cannot read (missing, unreadable or over 256 MiB)", path);
        return -1;
    }
    msg[0] = '\0';
    if (sbl__json_parse(text, len, root, msg, (int)sizeof(msg))) {
        sbl__ds_err(err, err_size, "%s: invalid JSON: %s", path, msg);
        free(text);
        return -1;
    }
    free(text);
    return 0;
}

/* ------------------------------------------------------------- dataset -- */

static int sbl__int_list(const sbl__jv *v, int *out, int max, int *count)
{
    int i;
    *count = 0;
    if (!v) return 0; /* optional */
    if (v->type != SBL_J_ARR || v->count > max) return -1;
    for (i = 0; i < v->count; ++i)
        if (sbl__jv_int(&v->items[i], 0, 1 << 30, &out[i])) return -1;
    *count = v->count;
    return 0;
}

/* cameras.json [frame][eye] matrix table. */
static int sbl__cam_mats(const sbl__jv *cams, const char *key, int frames, float (*dst)[2][16],
                         const char *path, char *err, int err_size)
{
    const sbl__jv *t = sbl__jv_get(cams, key);
    int f, e;
    if (!t || t->type != SBL_J_ARR || t->count < frames) {
        sbl__ds_err(err, err_size, "%s: '%s' missing or shorter than %d frames", path, key, frames);
        return -1;
    }
    for (f = 0; f < frames; ++f) {
        const sbl__jv *fe = sbl__jv_at(t, f);
        for (e = 0; e < 2; ++e) {
            if (sbl__jv_mat4(sbl__jv_at(fe, e), dst[f][e])) {
                sbl__ds_err(err, err_size, "%s: '%s'[%d][%d] is not a 4x4 matrix", path, key, f, e);
                return -1;
            }
        }
    }
    return 0;
}

static int sbl__is_num(const sbl__jv *v) { return v && v->type == SBL_J_NUM; }

void sbl_dataset_close(sbl_dataset *ds)
{
    if (!ds) return;
    free(ds->world_to_cam);
    free(ds->cam_to_world);
    free(ds->proj);
    free(ds->focal_px);
    memset(ds, 0, sizeof(*ds));
}

int sbl_dataset_open(sbl_dataset *ds, const char *dir, char *err, int err_size)
{
    char path[1100];
    sbl__jv meta, cams;
    const sbl__jv *v, *res;
    int f, e, status = -1;
    size_t n;

    if (!ds) return -1;
    memset(ds, 0, sizeof(*ds));
    memset(&meta, 0, sizeof(meta));
    memset(&cams, 0, sizeof(cams));
    if (!dir || (n = strlen(dir)) == 0 || n >= sizeof(ds->dir)) {
        sbl__ds_err(err, err_size, "sbl_dataset_open: bad directory name");
        return -1;
    }
    memcpy(ds->dir, dir, n + 1);
    while (n > 1 && ds->dir[n - 1] == '/') ds->dir[--n] = '\0';

    /* meta.json */
    snprintf(path, sizeof(path), "%s/meta.json", ds->dir);
    if (sbl__load_json(path, &meta, err, err_size)) goto fail;
    if (meta.type != SBL_J_OBJ) { sbl__ds_err(err, err_size, "%s: not a JSON object", path); goto fail; }
    if (sbl__jv_int(sbl__jv_get(&meta, "frames"), 1, 1000000, &ds->frames)) {
        sbl__ds_err(err, err_size, "%s: 'frames' missing or not a positive integer", path);
        goto fail;
    }
    res = sbl__jv_get(&meta, "resolution");
    if (!res || res->type != SBL_J_ARR || res->count != 2 ||
        sbl__jv_int(&res->items[0], 1, 1 << 16, &ds->width) || sbl__jv_int(&res->items[1], 1, 1 << 16, &ds->height)) {
        sbl__ds_err(err, err_size, "%s: 'resolution' must be [width, height]", path);
        goto fail;
    }
    v = sbl__jv_get(&meta, "ref_spp");
    if (v && sbl__jv_int(v, 0, 1 << 30, &ds->ref_spp)) {
        sbl__ds_err(err, err_size, "%s: 'ref_spp' not a non-negative integer", path);
        goto fail;
    }
    if (sbl__int_list(sbl__jv_get(&meta, "ladder_frames"), ds->ladder_frames, SBL_DATASET_MAX_LADDER,
                      &ds->ladder_frame_count) ||
        sbl__int_list(sbl__jv_get(&meta, "ladder_spp"), ds->ladder_spp, SBL_DATASET_MAX_LADDER,
                      &ds->ladder_spp_count)) {
        sbl__ds_err(err, err_size, "%s: 'ladder_frames'/'ladder_spp' must be lists of at most %d integers",
                    path, SBL_DATASET_MAX_LADDER);
        goto fail;
    }

    /* cameras.json */
    snprintf(path, sizeof(path), "%s/cameras.json", ds->dir);
    if (sbl__load_json(path, &cams, err, err_size)) goto fail;
    if (cams.type != SBL_J_OBJ) { sbl__ds_err(err, err_size, "%s: not a JSON object", path); goto fail; }
    res = sbl__jv_get(&cams, "resolution");
    if (res) {
        int w, h;
        if (res->type != SBL_J_ARR || res->count != 2 || sbl__jv_int(&res->items[0], 1, 1 << 16, &w) ||
            sbl__jv_int(&res->items[1], 1, 1 << 16, &h) || w != ds->width || h != ds->height) {
            sbl__ds_err(err, err_size, "%s: 'resolution' disagrees with meta.json (%dx%d)", path, ds->width, ds->height);
            goto fail;
        }
    }
    ds->world_to_cam = (float (*)[2][16])calloc((size_t)ds->frames, sizeof(*ds->world_to_cam));
    ds->cam_to_world = (float (*)[2][16])calloc((size_t)ds->frames, sizeof(*ds->cam_to_world));
    ds->proj = (float (*)[2][16])calloc((size_t)ds->frames, sizeof(*ds->proj));
    ds->focal_px = (float (*)[2])calloc((size_t)ds->frames, sizeof(*ds->focal_px));
    if (!ds->world_to_cam || !ds->cam_to_world || !ds->proj || !ds->focal_px) {
        sbl__ds_err(err, err_size, "sbl_dataset_open: out of memory");
        goto fail;
    }
    if (sbl__cam_mats(&cams, "world_to_cam", ds->frames, ds->world_to_cam, path, err, err_size) ||
        sbl__cam_mats(&cams, "cam_to_world", ds->frames, ds->cam_to_world, path, err, err_size) ||
        sbl__cam_mats(&cams, "proj", ds->frames, ds->proj, path, err, err_size))
        goto fail;

    /* focal_px: one number, or per frame, or per frame and eye. */
    v = sbl__jv_get(&cams, "focal_px");
    if (sbl__is_num(v)) {
        for (f = 0; f < ds->frames; ++f) ds->focal_px[f][0] = ds->focal_px[f][1] = (float)v->num;
    } else if (v && v->type == SBL_J_ARR && v->count >= ds->frames) {
        for (f = 0; f < ds->frames; ++f) {
            const sbl__jv *fv = &v->items[f];
            for (e = 0; e < 2; ++e) {
                const sbl__jv *x = fv->type == SBL_J_ARR ? sbl__jv_at(fv, e) : fv;
                if (!sbl__is_num(x)) { v = NULL; break; }
                ds->focal_px[f][e] = (float)x->num;
            }
            if (!v) break;
        }
    } else {
        v = NULL;
    }
    if (!v) {
        sbl__ds_err(err, err_size, "%s: 'focal_px' missing or malformed", path);
        goto fail;
    }
    for (f = 0; f < ds->frames; ++f) {
        if (!(ds->focal_px[f][0] > 0.0f && ds->focal_px[f][1] > 0.0f)) {
            sbl__ds_err(err, err_size, "%s: 'focal_px' must be positive", path);
            goto fail;
        }
    }
    v = sbl__jv_get(&cams, "baseline");
    if (!sbl__is_num(v) || !(v->num > 0.0)) {
        sbl__ds_err(err, err_size, "%s: 'baseline' missing or not positive", path);
        goto fail;
    }
    ds->baseline = (float)v->num;
    v = sbl__jv_get(&cams, "clip");
    if (v && v->type == SBL_J_ARR && v->count == 2 && sbl__is_num(&v->items[0]) && sbl__is_num(&v->items[1])) {
        ds->clip_near = (float)v->items[0].num;
        ds->clip_far = (float)v->items[1].num;
    }
    status = 0;

fail:
    sbl__jv_free(&meta);
    sbl__jv_free(&cams);
    if (status) sbl_dataset_close(ds);
    return status;
}

int sbl_dataset_path(const sbl_dataset *ds, const char *kind, int frame, int eye, char *path, int path_size)
{
    int n;
    if (!ds || !kind || !path || path_size <= 0 || eye < 0 || eye > 1 || frame < 0 || frame > 9999) return -1;
    n = snprintf(path, (size_t)path_size, "%s/exr/%s/%c_%04d.exr", ds->dir, kind, eye ? 'R' : 'L', frame);
    return (n < 0 || n >= path_size) ? -1 : 0;
}

static int sbl__file_exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fclose(f);
    return 1;
}

static const char *const sbl__rgb_names[3] = {
    "ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"
};

/* Read RGB and insist on the dataset's resolution. */
static int sbl__load_rgb(const sbl_dataset *ds, const char *path, float **rgb, char *err, int err_size)
{
    int w = 0, h = 0;
    if (sbl_exr_read(path, sbl__rgb_names, 3, rgb, &w, &h, err, err_size)) return -1;
    if (w != ds->width || h != ds->height) {
        sbl__ds_err(err, err_size, "%s: %dx%d, expected %dx%d", path, w, h, ds->width, ds->height);
        free(*rgb);
        *rgb = NULL;
        return -1;
    }
    return 0;
}

void sbl_dataset_frame_free(sbl_dataset_frame *f)
{
    if (!f) return;
    free(f->noisy);
    free(f->ref);
    free(f->depth);
    free(f->normal);
    free(f->id);
    free(f->motion);
    memset(f, 0, sizeof(*f));
}

int sbl_dataset_load(const sbl_dataset *ds, int frame, int eye, sbl_dataset_frame *out, char *err, int err_size)
{
    static const char *const gnames[7] = {
        "ViewLayer.Depth.Z", "ViewLayer.Normal.X", "ViewLayer.Normal.Y", "ViewLayer.Normal.Z",
        "ViewLayer.IndexOB.X", "ViewLayer.Vector.X", "ViewLayer.Vector.Y"
    };
    char path[1200];
    float *g = NULL;
    size_t i, np;
    int w = 0, h = 0;

    if (!out) return -1;
    memset(out, 0, sizeof(*out));
    if (!ds || !ds->frames || frame < 0 || frame >= ds->frames || eye < 0 || eye > 1) {
        sbl__ds_err(err, err_size, "sbl_dataset_load: frame %d eye %d out of range", frame, eye);
        return -1;
    }
    np = (size_t)ds->width * (size_t)ds->height;

    if (sbl_dataset_path(ds, "noisy", frame, eye, path, (int)sizeof(path)) ||
        sbl__load_rgb(ds, path, &out->noisy, err, err_size))
        goto fail;
    if (sbl_dataset_path(ds, "ref", frame, eye, path, (int)sizeof(path))) goto fail;
    if (sbl__file_exists(path) && sbl__load_rgb(ds, path, &out->ref, err, err_size)) goto fail;

    if (sbl_dataset_path(ds, "gbuf", frame, eye, path, (int)sizeof(path)) ||
        sbl_exr_read(path, gnames, 7, &g, &w, &h, err, err_size))
        goto fail;
    if (w != ds->width || h != ds->height) {
        sbl__ds_err(err, err_size, "%s: %dx%d, expected %dx%d", path, w, h, ds->width, ds->height);
        goto fail;
    }
    out->depth = (float *)malloc(np * sizeof(float));
    out->normal = (float *)malloc(np * 3 * sizeof(float));
    out->id = (float *)malloc(np * sizeof(float));
    out->motion = (float *)malloc(np * 2 * sizeof(float));
    if (!out->depth || !out->normal || !out->id || !out->motion) {
        sbl__ds_err(err, err_size, "sbl_dataset_load: out of memory");
        goto fail;
    }
    for (i = 0; i < np; ++i) {
        const float *s = g + 7 * i;
        out->depth[i] = s[0];
        out->normal[3 * i + 0] = s[1];
        out->normal[3 * i + 1] = s[2];
        out->normal[3 * i + 2] = s[3];
        out->id[i] = s[4];
        /* Blender's Vector.XY = p(t-1) - p(t) in pixels with +y up, so the
         * previous position in row-down coordinates is (u + X, v - Y). */
        out->motion[2 * i + 0] = s[5];
        out->motion[2 * i + 1] = -s[6];
    }
    free(g);
    return 0;

fail:
    free(g);
    sbl_dataset_frame_free(out);
    return -1;
}

int sbl_dataset_load_ladder(const sbl_dataset *ds, int frame, int eye, int spp, float **rgb, char *err, int err_size)
{
    char path[1200];
    int n;
    if (!rgb) return -1;
    *rgb = NULL;
    if (!ds || !ds->frames || frame < 0 || frame > 9999 || eye < 0 || eye > 1 || spp < 1 || spp > 999999) {
        sbl__ds_err(err, err_size, "sbl_dataset_load_ladder: bad arguments");
        return -1;
    }
    n = snprintf(path, sizeof(path), "%s/exr/ladder/%c_f%04d_s%03d.exr", ds->dir, eye ? 'R' : 'L', frame, spp);
    if (n < 0 || n >= (int)sizeof(path)) return -1;
    if (!sbl__file_exists(path)) {
        sbl__ds_err(err, err_size, "%s: no such ladder render", path);
        return -1;
    }
    return sbl__load_rgb(ds, path, rgb, err, err_size);
}
