/* sbl_png.h - the smallest PNG writer that is still a valid PNG: 8-bit RGB, no filtering,
   "deflate" with stored (uncompressed) blocks, so no compression library is needed. Files
   are about as large as the raw pixels; fine for contact sheets of test renders.

     int sbl_png_write_rgb8(const char *path, const unsigned char *rgb, int w, int h);
         rgb: w * h * 3 bytes, row 0 at the top. Returns 0, or -1 (with errno from stdio).

   Everything is static: include it where it is used. */
#ifndef SBL_PNG_H
#define SBL_PNG_H
#include <stdio.h>
#include <stddef.h>

static unsigned long sbl_png__crc_table[256];

static unsigned long sbl_png__crc(unsigned long crc, const unsigned char *p, size_t n)
{
    size_t i;
    if (!sbl_png__crc_table[1]) { /* CRC-32 (ISO-HDLC), reflected polynomial 0xEDB88320 */
        unsigned long c;
        int k, b;
        for (k = 0; k < 256; ++k) {
            c = (unsigned long)k;
            for (b = 0; b < 8; ++b) c = (c & 1ul) ? 0xEDB88320ul ^ (c >> 1) : c >> 1;
            sbl_png__crc_table[k] = c;
        }
    }
    crc ^= 0xFFFFFFFFul;
    for (i = 0; i < n; ++i) crc = sbl_png__crc_table[(crc ^ p[i]) & 0xFFul] ^ (crc >> 8);
    return crc ^ 0xFFFFFFFFul;
}

static void sbl_png__be32(unsigned char *p, unsigned long v)
{
    p[0] = (unsigned char)(v >> 24); p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);  p[3] = (unsigned char)v;
}

/* one chunk: length, type, data, CRC over type + data; data may be written in pieces by
   the caller between _begin and _end, the CRC is carried along */
typedef struct sbl_png__chunk { FILE *f; unsigned long crc; int bad; } sbl_png__chunk;

static void sbl_png__put(sbl_png__chunk *c, const unsigned char *p, size_t n)
{
    if (n && fwrite(p, 1, n, c->f) != n) c->bad = 1;
    c->crc = sbl_png__crc(c->crc, p, n);
}

static void sbl_png__begin(sbl_png__chunk *c, FILE *f, const char *type, unsigned long length)
{
    unsigned char len[4];
    c->f = f; c->crc = 0; c->bad = 0;
    sbl_png__be32(len, length);
    if (fwrite(len, 1, 4, f) != 4) c->bad = 1;
    sbl_png__put(c, (const unsigned char *)type, 4);
}

static int sbl_png__end(sbl_png__chunk *c)
{
    unsigned char crc[4];
    sbl_png__be32(crc, c->crc);
    if (fwrite(crc, 1, 4, c->f) != 4) c->bad = 1;
    return c->bad ? -1 : 0;
}

static int sbl_png_write_rgb8(const char *path, const unsigned char *rgb, int w, int h)
{
    static const unsigned char signature[8] = {137, 'P', 'N', 'G', 13, 10, 26, 10};
    const size_t row = (size_t)w * 3 + 1; /* filter byte + pixels */
    const size_t raw = row * (size_t)h, max_block = 65535;
    const size_t blocks = raw ? (raw + max_block - 1) / max_block : 1;
    const size_t idat = 2 + blocks * 5 + raw + 4; /* zlib header, block headers, data, Adler */
    unsigned char hdr[13], b[5];
    unsigned long s1 = 1, s2 = 0; /* Adler-32 */
    size_t done = 0, k;
    int y, rc = 0;
    sbl_png__chunk c;
    FILE *f;
    if (w <= 0 || h <= 0 || idat > 0x7FFFFFFFul) return -1;
    f = fopen(path, "wb");
    if (!f) return -1;
    if (fwrite(signature, 1, 8, f) != 8) rc = -1;
    sbl_png__be32(hdr, (unsigned long)w);
    sbl_png__be32(hdr + 4, (unsigned long)h);
    hdr[8] = 8; hdr[9] = 2; hdr[10] = 0; hdr[11] = 0; hdr[12] = 0; /* 8 bit, RGB */
    sbl_png__begin(&c, f, "IHDR", 13);
    sbl_png__put(&c, hdr, 13);
    rc |= sbl_png__end(&c);

    sbl_png__begin(&c, f, "IDAT", (unsigned long)idat);
    b[0] = 0x78; b[1] = 0x01; /* zlib: deflate, 32K window, no dictionary, check bits */
    sbl_png__put(&c, b, 2);
    /* the rows as one byte stream (filter 0 then the pixels), cut into stored blocks */
    for (y = 0; y < h; ++y) {
        const unsigned char *src = rgb + (size_t)y * (size_t)w * 3;
        for (k = 0; k < row; ++k) {
            unsigned char v = k == 0 ? 0 : src[k - 1];
            if (done % max_block == 0) { /* block header: BFINAL, BTYPE 00, LEN, NLEN */
                size_t len = raw - done < max_block ? raw - done : max_block;
                b[0] = (unsigned char)(done + len == raw ? 1 : 0);
                b[1] = (unsigned char)(len & 0xFF); b[2] = (unsigned char)(len >> 8);
                b[3] = (unsigned char)(~len & 0xFF); b[4] = (unsigned char)((~len >> 8) & 0xFF);
                sbl_png__put(&c, b, 5);
            }
            sbl_png__put(&c, &v, 1);
            s1 = (s1 + v) % 65521ul;
            s2 = (s2 + s1) % 65521ul;
            ++done;
        }
    }
    sbl_png__be32(b, (s2 << 16) | s1);
    sbl_png__put(&c, b, 4);
    rc |= sbl_png__end(&c);

    sbl_png__begin(&c, f, "IEND", 0);
    rc |= sbl_png__end(&c);
    if (fclose(f) != 0) rc = -1;
    return rc;
}
#endif
