/* scene_json: recursive-descent JSON parser with line tracking (see
 * scene_json.h). Nodes and decoded strings live in one arena of linked blocks
 * so a document is freed with a single call. */
#include "scene/scene_json.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { ARENA_BLOCK = 64 * 1024 };

typedef struct arena_block_t {
    struct arena_block_t *prev;
    size_t used, cap;
    max_align_t data[];
} arena_block_t;

typedef struct parser_t {
    const char *start;
    const char *p;
    const char *end;
    int line;
    const char *name;
    char *err;
    size_t err_size;
    bool failed;
    arena_block_t *arena;
    int depth;
    char open_char[SCENE_JSON_MAX_DEPTH];
    int open_line[SCENE_JSON_MAX_DEPTH];
} parser_t;

static void *arena_alloc(parser_t *ps, size_t size)
{
    size = (size + sizeof(max_align_t) - 1) & ~(sizeof(max_align_t) - 1);
    arena_block_t *b = ps->arena;
    if (!b || b->cap - b->used < size) {
        size_t cap = size > ARENA_BLOCK ? size : ARENA_BLOCK;
        arena_block_t *nb = malloc(sizeof *nb + cap);
        if (!nb) return NULL;
        nb->prev = b;
        nb->used = 0;
        nb->cap = cap;
        ps->arena = b = nb;
    }
    void *out = (char *)b->data + b->used;
    b->used += size;
    return out;
}

static void arena_free(arena_block_t *b)
{
    while (b) {
        arena_block_t *prev = b->prev;
        free(b);
        b = prev;
    }
}

__attribute__((format(printf, 2, 3))) static bool fail(parser_t *ps, const char *fmt, ...)
{
    if (ps->failed) return false;
    ps->failed = true;
    if (!ps->err || !ps->err_size) return false;
    int n = snprintf(ps->err, ps->err_size, "%s:%d: ", ps->name, ps->line);
    if (n < 0 || (size_t)n >= ps->err_size) return false;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(ps->err + n, ps->err_size - (size_t)n, fmt, ap);
    va_end(ap);
    return false;
}

/* Error at end of input: name the innermost container still open. */
static bool fail_eof(parser_t *ps, const char *what)
{
    /* Report the last line with content, not the empty one after a final
     * newline. */
    if (ps->p >= ps->end) {
        for (const char *q = ps->end; q > ps->start; q--) {
            char c = q[-1];
            if (c == '\n' && ps->line > 1) ps->line--;
            else if (c != ' ' && c != '\t' && c != '\r') break;
        }
    }
    if (ps->depth > 0) {
        int d = ps->depth - 1;
        return fail(ps, "unexpected end of file, expected %s (unclosed '%c' from line %d)", what,
                    ps->open_char[d], ps->open_line[d]);
    }
    return fail(ps, "unexpected end of file, expected %s", what);
}

static bool fail_char(parser_t *ps, const char *what)
{
    unsigned char c = (unsigned char)*ps->p;
    if (c >= 0x20 && c < 0x7f) return fail(ps, "unexpected character '%c', expected %s", c, what);
    return fail(ps, "unexpected byte 0x%02x, expected %s", c, what);
}

static void skip_ws(parser_t *ps)
{
    while (ps->p < ps->end) {
        char c = *ps->p;
        if (c == '\n') ps->line++;
        else if (c != ' ' && c != '\t' && c != '\r') return;
        ps->p++;
    }
}

static scene_json_t *new_node(parser_t *ps, scene_json_type_t type)
{
    scene_json_t *n = arena_alloc(ps, sizeof *n);
    if (!n) {
        fail(ps, "out of memory");
        return NULL;
    }
    memset(n, 0, sizeof *n);
    n->type = type;
    n->line = ps->line;
    return n;
}

static int hex_val(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

static bool read_hex4(parser_t *ps, const char *s, uint32_t *out)
{
    if (ps->end - s < 4) return fail_eof(ps, "4 hex digits after \\u");
    uint32_t v = 0;
    for (int i = 0; i < 4; i++) {
        int h = hex_val(s[i]);
        if (h < 0) return fail(ps, "invalid \\u escape: expected 4 hex digits");
        v = v << 4 | (uint32_t)h;
    }
    *out = v;
    return true;
}

static char *put_utf8(char *o, uint32_t cp)
{
    if (cp < 0x80) {
        *o++ = (char)cp;
    } else if (cp < 0x800) {
        *o++ = (char)(0xc0 | cp >> 6);
        *o++ = (char)(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
        *o++ = (char)(0xe0 | cp >> 12);
        *o++ = (char)(0x80 | (cp >> 6 & 0x3f));
        *o++ = (char)(0x80 | (cp & 0x3f));
    } else {
        *o++ = (char)(0xf0 | cp >> 18);
        *o++ = (char)(0x80 | (cp >> 12 & 0x3f));
        *o++ = (char)(0x80 | (cp >> 6 & 0x3f));
        *o++ = (char)(0x80 | (cp & 0x3f));
    }
    return o;
}

/* Bytes of the well-formed UTF-8 sequence at s (before end), 0 when it is
 * not one: a stray continuation byte, an overlong form, a surrogate, past
 * U+10FFFF or cut short (RFC 3629). */
static size_t utf8_len(const unsigned char *s, const unsigned char *end)
{
    unsigned char c = s[0];
    size_t n = c < 0x80 ? 1 : c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    if (n == 0 || (size_t)(end - s) < n) return 0;
    for (size_t i = 1; i < n; i++)
        if ((s[i] & 0xc0) != 0x80) return 0;
    if ((c == 0xe0 && s[1] < 0xa0) || (c == 0xed && s[1] > 0x9f) || (c == 0xf0 && s[1] < 0x90) ||
        (c == 0xf4 && s[1] > 0x8f))
        return 0;
    return n;
}

/* ps->p at the opening quote. Decoded text is never longer than the raw
 * span, so one allocation of the raw length suffices. */
static bool parse_string(parser_t *ps, const char **out, size_t *out_len)
{
    const char *s = ps->p + 1, *q = s;
    while (q < ps->end && *q != '"') {
        if ((unsigned char)*q < 0x20) break;
        q += (*q == '\\' && q + 1 < ps->end) ? 2 : 1;
    }
    if (q >= ps->end) {
        ps->p = ps->end;
        return fail_eof(ps, "closing '\"' of string");
    }
    if (*q != '"') {
        ps->p = q;
        if (*q == '\n') return fail(ps, "unterminated string (newline before closing '\"')");
        return fail(ps, "control character 0x%02x in string (escape it)", (unsigned char)*q);
    }
    char *buf = arena_alloc(ps, (size_t)(q - s) + 1);
    if (!buf) return fail(ps, "out of memory");
    char *o = buf;
    while (s < q) {
        if ((unsigned char)*s >= 0x80) {
            /* Checked here so that no message echoes bytes that are not text. */
            size_t n = utf8_len((const unsigned char *)s, (const unsigned char *)q);
            if (n == 0)
                return fail(ps, "invalid UTF-8 in a string (byte 0x%02x at offset %zu): a scene file is UTF-8 text",
                            (unsigned char)*s, (size_t)(s - ps->start));
            memcpy(o, s, n);
            o += n;
            s += n;
            continue;
        }
        if (*s != '\\') {
            *o++ = *s++;
            continue;
        }
        char e = s[1];
        s += 2;
        switch (e) {
        case '"': *o++ = '"'; break;
        case '\\': *o++ = '\\'; break;
        case '/': *o++ = '/'; break;
        case 'b': *o++ = '\b'; break;
        case 'f': *o++ = '\f'; break;
        case 'n': *o++ = '\n'; break;
        case 'r': *o++ = '\r'; break;
        case 't': *o++ = '\t'; break;
        case 'u': {
            uint32_t cp = 0;
            if (!read_hex4(ps, s, &cp)) return false;
            s += 4;
            if (cp == 0) return fail(ps, "\\u0000 is not allowed in strings");
            if (cp >= 0xdc00 && cp <= 0xdfff) return fail(ps, "lone low surrogate \\u%04x", cp);
            if (cp >= 0xd800 && cp <= 0xdbff) {
                uint32_t lo = 0;
                if (q - s < 6 || s[0] != '\\' || s[1] != 'u')
                    return fail(ps, "high surrogate \\u%04x not followed by a low surrogate", cp);
                if (!read_hex4(ps, s + 2, &lo)) return false;
                if (lo < 0xdc00 || lo > 0xdfff)
                    return fail(ps, "high surrogate \\u%04x not followed by a low surrogate", cp);
                s += 6;
                cp = 0x10000 + ((cp - 0xd800) << 10) + (lo - 0xdc00);
            }
            o = put_utf8(o, cp);
            break;
        }
        default:
            if ((unsigned char)e >= 0x20 && (unsigned char)e < 0x7f)
                return fail(ps, "invalid escape '\\%c' in string", e);
            return fail(ps, "invalid escape in string");
        }
    }
    *o = 0;
    *out = buf;
    *out_len = (size_t)(o - buf);
    ps->p = q + 1;
    return true;
}

static bool is_digit(char c) { return c >= '0' && c <= '9'; }

static bool parse_number(parser_t *ps, scene_json_t *n)
{
    const char *s = ps->p, *q = s;
    if (q < ps->end && *q == '-') q++;
    if (q >= ps->end || !is_digit(*q)) {
        ps->p = q;
        return q >= ps->end ? fail_eof(ps, "digit") : fail_char(ps, "digit");
    }
    if (*q == '0') {
        q++;
    } else {
        while (q < ps->end && is_digit(*q)) q++;
    }
    if (q < ps->end && *q == '.') {
        q++;
        if (q >= ps->end || !is_digit(*q)) {
            ps->p = q;
            return q >= ps->end ? fail_eof(ps, "digit after '.'") : fail_char(ps, "digit after '.'");
        }
        while (q < ps->end && is_digit(*q)) q++;
    }
    if (q < ps->end && (*q == 'e' || *q == 'E')) {
        q++;
        if (q < ps->end && (*q == '+' || *q == '-')) q++;
        if (q >= ps->end || !is_digit(*q)) {
            ps->p = q;
            return q >= ps->end ? fail_eof(ps, "exponent digit") : fail_char(ps, "exponent digit");
        }
        while (q < ps->end && is_digit(*q)) q++;
    }
    char buf[128];
    size_t len = (size_t)(q - s);
    if (len >= sizeof buf) return fail(ps, "number literal longer than %zu characters", sizeof buf - 1);
    memcpy(buf, s, len);
    buf[len] = 0;
    n->number = strtod(buf, NULL);
    if (!isfinite(n->number)) return fail(ps, "number %s is out of double range", buf);
    ps->p = q;
    return true;
}

static bool parse_literal(parser_t *ps, const char *word)
{
    size_t len = strlen(word);
    const char *q = ps->p;
    if ((size_t)(ps->end - q) < len || memcmp(q, word, len) != 0 ||
        (q + len < ps->end && ((q[len] >= 'a' && q[len] <= 'z') || (q[len] >= 'A' && q[len] <= 'Z') ||
                               is_digit(q[len]) || q[len] == '_')))
        return fail_char(ps, "a value (string, number, object, array, true, false or null)");
    ps->p += len;
    return true;
}

static scene_json_t *parse_value(parser_t *ps);

static bool push_open(parser_t *ps, char c)
{
    if (ps->depth >= SCENE_JSON_MAX_DEPTH)
        return fail(ps, "nesting deeper than %d levels", SCENE_JSON_MAX_DEPTH);
    ps->open_char[ps->depth] = c;
    ps->open_line[ps->depth] = ps->line;
    ps->depth++;
    return true;
}

static scene_json_t *parse_object(parser_t *ps, scene_json_t *obj)
{
    if (!push_open(ps, '{')) return NULL;
    ps->p++;
    skip_ws(ps);
    if (ps->p < ps->end && *ps->p == '}') {
        ps->p++;
        ps->depth--;
        return obj;
    }
    scene_json_t **tail = &obj->child;
    for (;;) {
        skip_ws(ps);
        if (ps->p >= ps->end) {
            fail_eof(ps, obj->count ? "string key" : "string key or '}'");
            return NULL;
        }
        if (*ps->p != '"') {
            fail_char(ps, obj->count ? "string key after ','" : "string key or '}'");
            return NULL;
        }
        int key_line = ps->line;
        const char *key;
        size_t key_len;
        if (!parse_string(ps, &key, &key_len)) return NULL;
        for (const scene_json_t *m = obj->child; m; m = m->next) {
            if (strcmp(m->key, key) == 0) {
                fail(ps, "duplicate key \"%s\" (first on line %d)", key, m->key_line);
                return NULL;
            }
        }
        skip_ws(ps);
        if (ps->p >= ps->end) {
            fail_eof(ps, "':' after key");
            return NULL;
        }
        if (*ps->p != ':') {
            fail_char(ps, "':' after key");
            return NULL;
        }
        ps->p++;
        scene_json_t *v = parse_value(ps);
        if (!v) return NULL;
        v->key = key;
        v->key_line = key_line;
        *tail = v;
        tail = &v->next;
        obj->count++;
        skip_ws(ps);
        if (ps->p >= ps->end) {
            fail_eof(ps, "',' or '}'");
            return NULL;
        }
        if (*ps->p == '}') break;
        if (*ps->p != ',') {
            fail_char(ps, "',' or '}' after object member");
            return NULL;
        }
        ps->p++;
    }
    ps->p++;
    ps->depth--;
    return obj;
}

static scene_json_t *parse_array(parser_t *ps, scene_json_t *arr)
{
    if (!push_open(ps, '[')) return NULL;
    ps->p++;
    skip_ws(ps);
    if (ps->p < ps->end && *ps->p == ']') {
        ps->p++;
        ps->depth--;
        return arr;
    }
    scene_json_t **tail = &arr->child;
    for (;;) {
        scene_json_t *v = parse_value(ps);
        if (!v) return NULL;
        *tail = v;
        tail = &v->next;
        arr->count++;
        skip_ws(ps);
        if (ps->p >= ps->end) {
            fail_eof(ps, "',' or ']'");
            return NULL;
        }
        if (*ps->p == ']') break;
        if (*ps->p != ',') {
            fail_char(ps, "',' or ']' after array element");
            return NULL;
        }
        ps->p++;
    }
    ps->p++;
    ps->depth--;
    return arr;
}

static scene_json_t *parse_value(parser_t *ps)
{
    skip_ws(ps);
    if (ps->p >= ps->end) {
        fail_eof(ps, "a value");
        return NULL;
    }
    char c = *ps->p;
    scene_json_t *n;
    switch (c) {
    case '{':
        n = new_node(ps, SCENE_JSON_OBJECT);
        return n ? parse_object(ps, n) : NULL;
    case '[':
        n = new_node(ps, SCENE_JSON_ARRAY);
        return n ? parse_array(ps, n) : NULL;
    case '"':
        n = new_node(ps, SCENE_JSON_STRING);
        return n && parse_string(ps, &n->string, &n->string_len) ? n : NULL;
    case 't':
    case 'f':
        n = new_node(ps, SCENE_JSON_BOOL);
        if (!n || !parse_literal(ps, c == 't' ? "true" : "false")) return NULL;
        n->boolean = c == 't';
        return n;
    case 'n':
        n = new_node(ps, SCENE_JSON_NULL);
        return n && parse_literal(ps, "null") ? n : NULL;
    default:
        if (c == '-' || is_digit(c)) {
            n = new_node(ps, SCENE_JSON_NUMBER);
            return n && parse_number(ps, n) ? n : NULL;
        }
        fail_char(ps, "a value (string, number, object, array, true, false or null)");
        return NULL;
    }
}

bool scene_json_parse(scene_json_doc_t *doc, const char *text, const char *name, char *err,
                      size_t err_size)
{
    parser_t ps = {
        .start = text,
        .p = text,
        .end = text + strlen(text),
        .line = 1,
        .name = name,
        .err = err,
        .err_size = err_size,
    };
    doc->root = NULL;
    doc->arena = NULL;
    /* A UTF-8 byte order mark (editors on Windows write one) is not JSON
     * (RFC 8259 8.1 lets a parser ignore it). */
    if (ps.end - ps.p >= 3 && memcmp(ps.p, "\xEF\xBB\xBF", 3) == 0) ps.p += 3;
    scene_json_t *root = parse_value(&ps);
    if (root) {
        skip_ws(&ps);
        if (ps.p < ps.end) {
            fail_char(&ps, "end of file after the top-level value");
            root = NULL;
        }
    }
    if (!root) {
        arena_free(ps.arena);
        return false;
    }
    doc->root = root;
    doc->arena = ps.arena;
    return true;
}

void scene_json_free(scene_json_doc_t *doc)
{
    arena_free(doc->arena);
    doc->root = NULL;
    doc->arena = NULL;
}

const scene_json_t *scene_json_get(const scene_json_t *obj, const char *key)
{
    if (!obj || obj->type != SCENE_JSON_OBJECT) return NULL;
    for (const scene_json_t *m = obj->child; m; m = m->next)
        if (strcmp(m->key, key) == 0) return m;
    return NULL;
}

const char *scene_json_type_name(scene_json_type_t type)
{
    static const char *const names[] = {"null", "boolean", "number", "string", "array", "object"};
    return names[type];
}
