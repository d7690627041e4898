/* sbl_exr.c - OpenEXR float I/O through OpenEXR's C API (OpenEXRCore, 3.1+).
 * Compile with -DSBL_NO_EXR to build a stub that only reports an error. */
#include "sbl_exr.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void sbl__exr_err(char *err, int err_size, const char *fmt, ...)
{
    va_list ap;
    if (!err || err_size <= 0) return;
    va_start(ap, fmt);
    vsnprintf(err, (size_t)err_size, fmt, ap);
    va_end(ap);
}

#ifdef SBL_NO_EXR

int sbl_exr_available(void) { return 0; }

int sbl_exr_read(const char *path, const char *const *channel_names,
                 int channel_count, float **out, int *width, int *height,
                 char *err, int err_size)
{
    (void)channel_names; (void)channel_count;
    if (out) *out = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    sbl__exr_err(err, err_size, "%s: built without OpenEXR", path ? path : "(null)");
    return -1;
}

int sbl_exr_write(const char *path, const float *data, int width, int height,
                  int channels, const char *const *channel_names,
                  char *err, int err_size)
{
    (void)data; (void)width; (void)height; (void)channels; (void)channel_names;
    sbl__exr_err(err, err_size, "%s: built without OpenEXR", path ? path : "(null)");
    return -1;
}

#else /* !SBL_NO_EXR */

/* The C headers use anonymous unions (C11); silence -pedantic for them only. */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#include <OpenEXR/openexr.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#define SBL_EXR_MAX_CHANNELS 1024

int sbl_exr_available(void) { return 1; }

/* The library's default handler prints to stderr; callers get err instead. */
static void sbl__exr_quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt; (void)code; (void)msg;
}

static int sbl__exr_find(const char *const *names, int count, const char *name)
{
    int k;
    for (k = 0; k < count; ++k)
        if (strcmp(names[k], name) == 0) return k;
    return -1;
}

/* Point every requested decoder channel at its slot in the interleaved
 * destination block starting at dst (first pixel of the chunk). */
static void sbl__exr_bind_decode(exr_decode_pipeline_t *dec, const char *const *names,
                                 int count, float *dst, int width)
{
    int c;
    for (c = 0; c < dec->channel_count; ++c) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        int k = sbl__exr_find(names, count, ch->channel_name);
        if (k < 0) {
            ch->decode_to_ptr = NULL; /* skipped by the library */
            continue;
        }
        ch->decode_to_ptr = (uint8_t *)(dst + k);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = 4;
        ch->user_pixel_stride = (int32_t)(count * 4);
        ch->user_line_stride = (int32_t)((size_t)width * (size_t)count * 4);
    }
}

/* Decode one chunk (scanline block or tile) whose top-left pixel is (x0, y0)
 * relative to the data window. */
static exr_result_t sbl__exr_decode_chunk(exr_context_t ctxt, int part, const exr_chunk_info_t *ci,
                                          exr_decode_pipeline_t *dec, int *dec_init,
                                          const char *const *names, int count,
                                          float *buf, int width, int x0, int y0)
{
    exr_result_t rv;
    if (!*dec_init) {
        rv = exr_decoding_initialize(ctxt, part, ci, dec);
        if (rv != EXR_ERR_SUCCESS) return rv;
        *dec_init = 1;
    } else {
        rv = exr_decoding_update(ctxt, part, ci, dec);
        if (rv != EXR_ERR_SUCCESS) return rv;
    }
    sbl__exr_bind_decode(dec, names, count, buf + ((size_t)y0 * (size_t)width + (size_t)x0) * (size_t)count, width);
    /* Re-chosen per chunk: the routine depends on the pointers just set. */
    rv = exr_decoding_choose_default_routines(ctxt, part, dec);
    if (rv != EXR_ERR_SUCCESS) return rv;
    return exr_decoding_run(ctxt, part, dec);
}

int sbl_exr_read(const char *path, const char *const *channel_names,
                 int channel_count, float **out, int *width, int *height,
                 char *err, int err_size)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_attr_box2i_t dw;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    exr_result_t rv;
    int dec_init = 0, nparts = 0, part = -1, p, k, w, h, status = -1;
    float *buf = NULL;
    const char *what = "";

    if (out) *out = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    if (!path || !channel_names || !out || !width || !height ||
        channel_count < 1 || channel_count > SBL_EXR_MAX_CHANNELS) {
        sbl__exr_err(err, err_size, "sbl_exr_read: invalid arguments");
        return -1;
    }
    for (k = 0; k < channel_count; ++k) {
        if (!channel_names[k]) {
            sbl__exr_err(err, err_size, "sbl_exr_read: channel name %d is NULL", k);
            return -1;
        }
        if (sbl__exr_find(channel_names, k, channel_names[k]) >= 0) {
            sbl__exr_err(err, err_size, "sbl_exr_read: channel '%s' requested twice", channel_names[k]);
            return -1;
        }
    }

    init.error_handler_fn = sbl__exr_quiet;
    rv = exr_start_read(&ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        sbl__exr_err(err, err_size, "%s: cannot open as EXR (%s)", path, exr_get_default_error_message(rv));
        return -1;
    }

    what = "part count";
    if ((rv = exr_get_count(ctxt, &nparts)) != EXR_ERR_SUCCESS) goto exr_fail;
    for (p = 0; p < nparts && part < 0; ++p) {
        const exr_attr_chlist_t *cl = NULL;
        exr_storage_t st;
        int all = 1;
        if (exr_get_storage(ctxt, p, &st) != EXR_ERR_SUCCESS) continue;
        if (st != EXR_STORAGE_SCANLINE && st != EXR_STORAGE_TILED) continue; /* deep */
        if (exr_get_channels(ctxt, p, &cl) != EXR_ERR_SUCCESS || !cl) continue;
        for (k = 0; k < channel_count && all; ++k) {
            int c, found = 0;
            for (c = 0; c < cl->num_channels; ++c) {
                const exr_attr_chlist_entry_t *e = &cl->entries[c];
                if (e->name.str && strcmp(e->name.str, channel_names[k]) == 0) {
                    if (e->x_sampling != 1 || e->y_sampling != 1) {
                        sbl__exr_err(err, err_size, "%s: channel '%s' is subsampled (unsupported)", path, channel_names[k]);
                        goto fail;
                    }
                    found = 1;
                    break;
                }
            }
            all = found;
        }
        if (all) { part = p; storage = st; }
    }
    if (part < 0) {
        /* Name a missing channel of part 0 to make typos obvious. */
        const exr_attr_chlist_t *cl = NULL;
        const char *missing = channel_names[0];
        if (nparts > 0 && exr_get_channels(ctxt, 0, &cl) == EXR_ERR_SUCCESS && cl) {
            for (k = 0; k < channel_count; ++k) {
                int c, found = 0;
                for (c = 0; c < cl->num_channels; ++c)
                    if (cl->entries[c].name.str && strcmp(cl->entries[c].name.str, channel_names[k]) == 0) found = 1;
                if (!found) { missing = channel_names[k]; break; }
            }
        }
        sbl__exr_err(err, err_size, "%s: no image part has all %d requested channels (part 0 lacks '%s')",
                     path, channel_count, missing);
        goto fail;
    }

    what = "data window";
    if ((rv = exr_get_data_window(ctxt, part, &dw)) != EXR_ERR_SUCCESS) goto exr_fail;
    if (dw.max.x < dw.min.x || dw.max.y < dw.min.y ||
        (double)dw.max.x - dw.min.x + 1.0 > 1e6 || (double)dw.max.y - dw.min.y + 1.0 > 1e6) {
        sbl__exr_err(err, err_size, "%s: bad data window", path);
        goto fail;
    }
    w = dw.max.x - dw.min.x + 1;
    h = dw.max.y - dw.min.y + 1;
    if ((double)w * h * channel_count * sizeof(float) > 4.0e9) {
        sbl__exr_err(err, err_size, "%s: image too large (%dx%d)", path, w, h);
        goto fail;
    }
    /* calloc: pixels of missing chunks stay 0 rather than garbage. */
    buf = (float *)calloc((size_t)w * (size_t)h * (size_t)channel_count, sizeof(float));
    if (!buf) {
        sbl__exr_err(err, err_size, "%s: out of memory", path);
        goto fail;
    }

    if (storage == EXR_STORAGE_SCANLINE) {
        int32_t lpc = 0, y;
        exr_chunk_info_t ci;
        what = "scanlines per chunk";
        if ((rv = exr_get_scanlines_per_chunk(ctxt, part, &lpc)) != EXR_ERR_SUCCESS) goto exr_fail;
        if (lpc < 1) { rv = EXR_ERR_CORRUPT_CHUNK; goto exr_fail; }
        for (y = dw.min.y; y <= dw.max.y; y += lpc) {
            what = "scanline chunk";
            if ((rv = exr_read_scanline_chunk_info(ctxt, part, y, &ci)) != EXR_ERR_SUCCESS) goto exr_fail;
            /* ci.start_y can precede dw.min.y only for a corrupt file. */
            if (ci.start_y < dw.min.y || ci.start_y + ci.height - 1 > dw.max.y) { rv = EXR_ERR_CORRUPT_CHUNK; goto exr_fail; }
            if ((rv = sbl__exr_decode_chunk(ctxt, part, &ci, &dec, &dec_init, channel_names, channel_count,
                                            buf, w, 0, ci.start_y - dw.min.y)) != EXR_ERR_SUCCESS) goto exr_fail;
            if (y > dw.max.y - lpc) break; /* avoid int overflow of y += lpc */
        }
    } else {
        uint32_t tw = 0, th = 0;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        int tx, ty, ntx, nty;
        exr_chunk_info_t ci;
        what = "tile descriptor";
        if ((rv = exr_get_tile_descriptor(ctxt, part, &tw, &th, &lm, &rm)) != EXR_ERR_SUCCESS) goto exr_fail;
        if (tw < 1 || th < 1) { rv = EXR_ERR_INVALID_ATTR; goto exr_fail; }
        ntx = (int)(((uint32_t)w + tw - 1) / tw);
        nty = (int)(((uint32_t)h + th - 1) / th);
        for (ty = 0; ty < nty; ++ty) {
            for (tx = 0; tx < ntx; ++tx) {
                what = "tile chunk"; /* level (0,0) = full resolution for mip/rip maps */
                if ((rv = exr_read_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &ci)) != EXR_ERR_SUCCESS) goto exr_fail;
                if ((uint32_t)tx * tw + (uint32_t)ci.width > (uint32_t)w ||
                    (uint32_t)ty * th + (uint32_t)ci.height > (uint32_t)h) { rv = EXR_ERR_CORRUPT_CHUNK; goto exr_fail; }
                if ((rv = sbl__exr_decode_chunk(ctxt, part, &ci, &dec, &dec_init, channel_names, channel_count,
                                                buf, w, (int)((uint32_t)tx * tw), (int)((uint32_t)ty * th))) != EXR_ERR_SUCCESS)
                    goto exr_fail;
            }
        }
    }

    *out = buf;
    buf = NULL;
    *width = w;
    *height = h;
    status = 0;
    goto done;

exr_fail:
    sbl__exr_err(err, err_size, "%s: %s: %s", path, what, exr_get_default_error_message(rv));
fail:
done:
    if (dec_init) exr_decoding_destroy(ctxt, &dec);
    exr_finish(&ctxt);
    free(buf);
    return status;
}

/* OpenEXRCore 3.1.5 stores garbage when a ZIP chunk does not compress (it
 * flags the chunk as raw without copying the raw bytes; 1-spp noise's last
 * 4-row chunk hits this). Wrap the default compressor and store the packed
 * bytes ourselves in that case; harmless on fixed versions. */
typedef struct sbl__exr_compress_wrap {
    exr_result_t (*compress)(exr_encode_pipeline_t *);
} sbl__exr_compress_wrap;

static exr_result_t sbl__exr_compress(exr_encode_pipeline_t *enc)
{
    const sbl__exr_compress_wrap *w = (const sbl__exr_compress_wrap *)enc->encoding_user_data;
    exr_result_t rv = w->compress(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes >= enc->packed_bytes &&
        enc->compressed_alloc_size >= enc->packed_bytes && enc->compressed_buffer != enc->packed_buffer) {
        memcpy(enc->compressed_buffer, enc->packed_buffer, (size_t)enc->packed_bytes);
        enc->compressed_bytes = (size_t)enc->packed_bytes;
    }
    return rv;
}

int sbl_exr_write(const char *path, const float *data, int width, int height,
                  int channels, const char *const *channel_names,
                  char *err, int err_size)
{
    static const char *const def1[] = { "Y" };
    static const char *const def2[] = { "R", "G" };
    static const char *const def3[] = { "R", "G", "B" };
    static const char *const def4[] = { "R", "G", "B", "A" };
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    sbl__exr_compress_wrap wrap;
    exr_result_t rv;
    int part = 0, enc_init = 0, k, started = 0, created = 0;
    int32_t lpc = 0, y;
    const char *what = "";
    const char *const *names = channel_names;

    if (!path || !data || width < 1 || height < 1 || channels < 1 || channels > SBL_EXR_MAX_CHANNELS ||
        (!names && channels > 4)) {
        sbl__exr_err(err, err_size, "sbl_exr_write: invalid arguments");
        return -1;
    }
    if ((double)width * channels * 4.0 > 2.0e9) {
        sbl__exr_err(err, err_size, "sbl_exr_write: image too wide");
        return -1;
    }
    if (!names) names = channels == 1 ? def1 : channels == 2 ? def2 : channels == 3 ? def3 : def4;
    for (k = 0; k < channels; ++k) {
        if (!names[k] || !names[k][0] || sbl__exr_find(names, k, names[k]) >= 0) {
            sbl__exr_err(err, err_size, "sbl_exr_write: channel name %d empty or repeated", k);
            return -1;
        }
    }

    init.error_handler_fn = sbl__exr_quiet;
    what = "create";
    if ((rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init)) != EXR_ERR_SUCCESS) goto exr_fail;
    started = created = 1;
    what = "header";
    if ((rv = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part)) != EXR_ERR_SUCCESS) goto exr_fail;
    if ((rv = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_ZIP)) != EXR_ERR_SUCCESS)
        goto exr_fail;
    for (k = 0; k < channels; ++k)
        if ((rv = exr_add_channel(ctxt, part, names[k], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1)) != EXR_ERR_SUCCESS)
            goto exr_fail;
    if ((rv = exr_write_header(ctxt)) != EXR_ERR_SUCCESS) goto exr_fail;
    if ((rv = exr_get_scanlines_per_chunk(ctxt, part, &lpc)) != EXR_ERR_SUCCESS) goto exr_fail;
    if (lpc < 1) { rv = EXR_ERR_INVALID_ATTR; goto exr_fail; }

    what = "pixels";
    for (y = 0; y < height; y += lpc) {
        exr_chunk_info_t ci;
        int c;
        if ((rv = exr_write_scanline_chunk_info(ctxt, part, y, &ci)) != EXR_ERR_SUCCESS) goto exr_fail;
        /* A fresh pipeline per chunk keeps the wrapped compress_fn simple. */
        if ((rv = exr_encoding_initialize(ctxt, part, &ci, &enc)) != EXR_ERR_SUCCESS) goto exr_fail;
        enc_init = 1;
        /* The encoder lists channels sorted by name: bind each by name. */
        for (c = 0; c < enc.channel_count; ++c) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            k = sbl__exr_find(names, channels, ch->channel_name);
            if (k < 0) { rv = EXR_ERR_INVALID_ARGUMENT; goto exr_fail; }
            ch->encode_from_ptr = (const uint8_t *)(data + ((size_t)ci.start_y * (size_t)width) * (size_t)channels + (size_t)k);
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = 4;
            ch->user_pixel_stride = (int32_t)(channels * 4);
            ch->user_line_stride = (int32_t)((size_t)width * (size_t)channels * 4);
        }
        if ((rv = exr_encoding_choose_default_routines(ctxt, part, &enc)) != EXR_ERR_SUCCESS) goto exr_fail;
        if (enc.compress_fn) {
            wrap.compress = enc.compress_fn;
            enc.encoding_user_data = &wrap;
            enc.compress_fn = sbl__exr_compress;
        }
        if ((rv = exr_encoding_run(ctxt, part, &enc)) != EXR_ERR_SUCCESS) goto exr_fail;
        exr_encoding_destroy(ctxt, &enc);
        memset(&enc, 0, sizeof(enc));
        enc_init = 0;
    }
    what = "finish";
    started = 0;
    if ((rv = exr_finish(&ctxt)) != EXR_ERR_SUCCESS) goto exr_fail;
    return 0;

exr_fail:
    sbl__exr_err(err, err_size, "%s: write %s: %s", path, what, exr_get_default_error_message(rv));
    if (enc_init) exr_encoding_destroy(ctxt, &enc);
    if (started) exr_finish(&ctxt);
    if (created) remove(path); /* no half-written file left behind */
    return -1;
}

#endif /* SBL_NO_EXR */
