/* Replays inputs through the fuzz target without libFuzzer: each argument is a file, or a
 * folder whose files are all read (the committed crashes, then any corpus). A crash is the
 * test's failure; the file being read is printed first so that the failure names it. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay_file(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (file == NULL) {
        fprintf(stderr, "cannot open %s\n", path);
        return 1;
    }
    size_t capacity = 4096, size = 0;
    uint8_t *data = malloc(capacity);
    for (size_t n; data != NULL && (n = fread(data + size, 1, capacity - size, file)) > 0;) {
        size += n;
        if (size == capacity) {
            uint8_t *grown = realloc(data, 2 * capacity);
            if (grown == NULL) {
                free(data);
                data = NULL;
                break;
            }
            data = grown;
            capacity *= 2;
        }
    }
    int failed = ferror(file) || data == NULL;
    fclose(file);
    if (failed) {
        fprintf(stderr, "cannot read %s\n", path);
        free(data);
        return 1;
    }
    fprintf(stderr, "replaying %s (%zu bytes)\n", path, size);
    LLVMFuzzerTestOneInput(data, size);
    free(data);
    return 0;
}

int main(int argc, char **argv)
{
    int failures = 0, replayed = 0;
    for (int i = 1; i < argc; ++i) {
        DIR *folder = opendir(argv[i]);
        if (folder == NULL) {
            failures += replay_file(argv[i]);
            ++replayed;
            continue;
        }
        for (struct dirent *entry; (entry = readdir(folder)) != NULL;) {
            if (entry->d_name[0] == '.') {
                continue; /* ".", ".." and hidden files */
            }
            size_t length = strlen(argv[i]) + strlen(entry->d_name) + 2;
            char *path = malloc(length);
            if (path == NULL) {
                ++failures;
                break;
            }
            snprintf(path, length, "%s/%s", argv[i], entry->d_name);
            failures += replay_file(path);
            ++replayed;
            free(path);
        }
        closedir(folder);
    }
    fprintf(stderr, "%d inputs replayed\n", replayed);
    return failures > 0 || replayed == 0;
}
