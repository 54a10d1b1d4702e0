/* The modelDescription reader: a document read into its arrays (entities, quotes, comments,
 * CDATA, defaults of initial, dependencies), malformed XML named by its line, hostile nesting,
 * FMI 1.0 in FMI 2.0's words, and a little fuzzing: tens of thousands of mutations of a valid
 * FMI 2.0 and a valid FMI 1.0 document, each read without
 * a memory error (run under AddressSanitizer) and either accepted or refused with a reason. */
#include <string.h>

#include "test_support.h"

static const char DOCUMENT[] =
    "\xEF\xBB\xBF<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<!-- a comment before the root -->\n"
    "<fmiModelDescription fmiVersion=\"2.0\" modelName='m &amp; n' guid=\"{g}\">\n"
    "  <CoSimulation modelIdentifier=\"m\" canGetAndSetFMUstate=\"true\"/>\n"
    "  <TypeDefinitions>\n"
    "    <SimpleType name=\"Angle\" description=\"an angle\"><Real unit=\"rad\"/></SimpleType>\n"
    "  </TypeDefinitions>\n"
    "  <?tool some processing instruction?>\n"
    "  <ModelVariables>\n"
    "    <ScalarVariable name=\"u\" valueReference=\"0\" causality=\"input\"\n"
    "        description=\"a&#10;b&#x20AC;\tc &lt;&gt;&quot;&apos;\">\n"
    "      <Real declaredType=\"Angle\" start=\" 1.5e3 \"/><![CDATA[ <not markup> ]]>\n"
    "    </ScalarVariable>\n"
    "    <ScalarVariable name=\"y\" valueReference=\"4294967295\" causality=\"output\">\n"
    "      <Integer/>\n"
    "    </ScalarVariable>\n"
    "    <ScalarVariable name=\"p\" valueReference=\"2\" causality=\"parameter\" "
    "variability=\"fixed\">\n"
    "      <Boolean start=\"true\"/>\n"
    "    </ScalarVariable>\n"
    "    <ScalarVariable name=\"t\" valueReference=\"3\" causality=\"independent\">"
    "<Real derivative=\" 1\"/></ScalarVariable>\n"
    "  </ModelVariables>\n"
    "  <ModelStructure>\n"
    "    <Outputs><Unknown index=\"2\" dependencies=\" 1\t3 \"/></Outputs>\n"
    "  </ModelStructure>\n"
    "</fmiModelDescription>\n";

/* FMI 1.0: a parameter is a variability, internal a causality, the types are <Type> with a
 * RealType; no ModelStructure; Co-Simulation under Implementation. */
static const char DOCUMENT_FMI1[] =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<fmiModelDescription fmiVersion=\"1.0\" modelName=\"m\" modelIdentifier=\"m\" "
    "guid=\"{g}\" numberOfContinuousStates=\"1\">\n"
    "  <TypeDefinitions>\n"
    "    <Type name=\"Angle\"><RealType quantity=\"angle\" unit=\"rad\"/></Type>\n"
    "  </TypeDefinitions>\n"
    "  <ModelVariables>\n"
    "    <ScalarVariable name=\"u\" valueReference=\"0\" causality=\"input\">\n"
    "      <Real declaredType=\"Angle\" start=\"1\" fixed=\"true\"/>\n"
    "    </ScalarVariable>\n"
    "    <ScalarVariable name=\"k\" valueReference=\"1\" variability=\"parameter\">"
    "<Real start=\"2\"/></ScalarVariable>\n"
    "    <ScalarVariable name=\"y\" valueReference=\"2\" causality=\"output\">\n"
    "      <Real/><DirectDependency><Name>u</Name></DirectDependency>\n"
    "    </ScalarVariable>\n"
    "    <ScalarVariable name=\"z\" valueReference=\"2\" causality=\"output\" "
    "alias=\"negatedAlias\"><Real/></ScalarVariable>\n"
    "    <ScalarVariable name=\"x\" valueReference=\"3\" causality=\"none\" "
    "variability=\"discrete\"><Integer/></ScalarVariable>\n"
    "  </ModelVariables>\n"
    "  <Implementation><CoSimulation_StandAlone>\n"
    "    <Capabilities canHandleVariableCommunicationStepSize=\"true\"/>\n"
    "  </CoSimulation_StandAlone></Implementation>\n"
    "</fmiModelDescription>\n";

static const char *text(const ssx_md *md, uint32_t offset)
{
    return md->strings + offset;
}

static void reads_a_document(void)
{
    ssx_md *md = ssx_md_read(DOCUMENT, strlen(DOCUMENT));
    CHECK(md != NULL);
    CHECK(md->error.problem == SSX_MD_OK);
    CHECK(md->variable_count == 4);
    CHECK(ssx_md_find(md, "p") == 2);
    CHECK(ssx_md_find(md, "q") == -1);
    CHECK(strcmp(text(md, md->description[0]), "a\nb\xE2\x82\xAC c <>\"'") == 0);
    CHECK(strcmp(text(md, md->start[0]), " 1.5e3 ") == 0);
    CHECK(md->declared_type[0] == 0 && md->unit[0] == 0);
    CHECK(strcmp(text(md, md->types[0].unit), "rad") == 0);
    CHECK(strcmp(text(md, md->types[0].description), "an angle") == 0);
    CHECK(md->value_reference[1] == 4294967295u);
    CHECK(md->type[1] == SSX_MD_INTEGER && md->initial[1] == SSX_MD_CALCULATED);
    CHECK(md->causality[2] == SSX_MD_PARAMETER && md->initial[2] == SSX_MD_EXACT);
    CHECK(md->initial[3] == SSX_MD_NONE && md->variability[3] == SSX_MD_CONTINUOUS);
    CHECK(md->output_count == 1 && md->output[0] == 1 && md->dependency_count[0] == 2);
    CHECK(md->dependencies[0] == 0 && md->dependencies[1] == 2);
    /* the derivative attribute, an index from 1 (0: none) */
    CHECK(md->derivative[0] == 0 && md->derivative[1] == 0 && md->derivative[3] == 1);
    int model_name = 0;
    for (size_t i = 0; i < md->attribute_count; ++i) {
        if (strcmp(text(md, md->attributes[i].name), "modelName") == 0) {
            model_name = strcmp(text(md, md->attributes[i].value), "m & n") == 0;
        }
    }
    CHECK(model_name);
    char joined[32];
    CHECK(ssx_md_join(md, md->name, 4, NULL, 0) == 7); /* three separators */
    CHECK(ssx_md_join(md, md->name, 4, joined, sizeof joined) == 7);
    CHECK(memcmp(joined, "u\0y\0p\0t", 7) == 0);
    /* an empty text alone copies nothing: out may be NULL (UBSan: memcpy to NULL) */
    uint32_t empty = 0;
    CHECK(ssx_md_join(md, &empty, 1, NULL, 0) == 0);
    CHECK(strcmp(ssx_md_word_text(SSX_MD_CALCULATED_PARAMETER), "calculatedParameter") == 0);
    ssx_md_free(md);
}

/* The reading of `document` stops with `problem` at `line`; for XML, detail says `detail`. */
static void reads_fmi1_in_fmi2_words(void)
{
    ssx_md *md = ssx_md_read(DOCUMENT_FMI1, strlen(DOCUMENT_FMI1));
    CHECK(md != NULL);
    CHECK(md->error.problem == SSX_MD_OK);
    CHECK(md->variable_count == 5);
    CHECK(md->causality[0] == SSX_MD_INPUT && md->variability[0] == SSX_MD_CONTINUOUS);
    CHECK(md->causality[1] == SSX_MD_PARAMETER && md->variability[1] == SSX_MD_FIXED);
    CHECK(md->causality[2] == SSX_MD_OUTPUT);
    CHECK(md->causality[3] == SSX_MD_LOCAL); /* a negated alias is no port */
    CHECK(md->causality[4] == SSX_MD_LOCAL && md->variability[4] == SSX_MD_DISCRETE);
    for (size_t i = 0; i < md->variable_count; ++i) {
        CHECK(md->initial[i] == SSX_MD_NONE); /* FMI 1.0 has none */
    }
    CHECK(strcmp(text(md, md->types[0].type), "Real") == 0);
    CHECK(strcmp(text(md, md->types[0].unit), "rad") == 0 && md->declared_type[0] == 0);
    /* no ModelStructure: the output depends on everything */
    CHECK(md->output_count == 1 && md->output[0] == 2 && md->dependency_count[0] == -1);
    int capabilities = 0;
    for (size_t i = 0; i < md->attribute_count; ++i) {
        capabilities += strcmp(text(md, md->attributes[i].element), "Capabilities") == 0;
    }
    CHECK(capabilities == 1);
    ssx_md_free(md);
    /* a word FMI 1.0 does not have */
    const char *bad = "<fmiModelDescription fmiVersion=\"1.0\"><ModelVariables>"
                      "<ScalarVariable name=\"v\" valueReference=\"0\" causality=\"local\">"
                      "<Real/></ScalarVariable></ModelVariables></fmiModelDescription>";
    md = ssx_md_read(bad, strlen(bad));
    CHECK(md->error.problem == SSX_MD_BAD_COMBINATION && strcmp(md->error.text, "local") == 0);
    ssx_md_free(md);
}

static void refused(const char *document, ssx_md_problem problem, size_t line, const char *detail)
{
    ssx_md *md = ssx_md_read(document, strlen(document));
    CHECK(md != NULL);
    if (md->error.problem != problem || md->error.line != line ||
        (detail != NULL && strcmp(md->error.detail, detail) != 0)) {
        fprintf(stderr, "%s\n-> problem %d line %zu: %s\n", document, md->error.problem,
                md->error.line, md->error.detail);
        exit(1);
    }
    ssx_md_free(md);
}

static void names_what_is_malformed(void)
{
    const char *root = "<fmiModelDescription fmiVersion=\"2.0\">";
    char document[512];
    struct {
        const char *body;
        size_t line;
        const char *detail;
    } cases[] = {
        {"\n<a></b>", 2, "end tag </b> does not match <a> of line 2"},
        {"\n\n<a b=1/>", 3, "expected a quoted value of the attribute b"},
        {"<a b='1' b='2'/>", 1, "attribute b appears twice in <a>"},
        {"<a b='1'c='2'/>", 1, "expected an attribute or the end of the tag <a>"},
        {"<a b='<'/>", 1, "'<' in the value of the attribute b"},
        {"\n<a b='&nbsp;'/>", 2, "'&nbsp...' is neither a predefined entity (&lt; &gt; &amp; "
                                 "&apos; &quot;) nor a character reference"},
        {"<a b='&#0;'/>", 1, "'&#0...' is neither a predefined entity (&lt; &gt; &amp; &apos; "
                             "&quot;) nor a character reference"},
        {"<a>\x01</a>", 1, "character U+0001 is not allowed in XML"},
        {"<a>\xC3\x28</a>", 1, "invalid UTF-8 (a sequence starting with byte 0xC3)"},
        {"<a>\xED\xA0\x80</a>", 1, "invalid UTF-8 (a sequence starting with byte 0xED)"},
        {"<a>]]></a>", 1, "']]>' in text"},
        {"<!-- a -- b -->", 1, "'--' inside a comment"},
        {"\n<!-- open", 2, "a comment is not closed"},
        {"<![CDATA[ open", 1, "a CDATA section is not closed"},
        {"<?xml version='1.0'?>", 1, "an XML declaration is allowed only at the start"},
        {"<!ENTITY x 'y'>", 1, "markup '<!' is not allowed here"},
        {"<a", 1, "the document ends inside the tag <a>"},
        {"\n<a>", 2, "the document ends inside <a> of line 2"},
        {"</fmiModelDescription>text", 1, "content after the root element"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        snprintf(document, sizeof document, "%s%s", root, cases[i].body);
        refused(document, SSX_MD_NOT_XML, cases[i].line, cases[i].detail);
    }
    refused("", SSX_MD_NOT_XML, 1, "no root element");
    refused("text", SSX_MD_NOT_XML, 1, "text before the root element");
    refused("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?><a/>", SSX_MD_NOT_XML, 1,
            "encoding ISO-8859-1 is not supported (FMI 2.0 requires UTF-8)");
    refused("<!DOCTYPE a [<!ENTITY b 'c'>]><a/>", SSX_MD_NOT_XML, 1,
            "a DOCTYPE is not accepted in a modelDescription");
    refused("<a/>", SSX_MD_NO_FMI_ROOT, 1, NULL);
    /* an end tag where the root element belongs: nothing is open (it read before the stack) */
    refused("</a>", SSX_MD_NOT_XML, 1, "end tag </a> without a start tag");
    refused("<!-- c -->\n</fmiModelDescription>", SSX_MD_NOT_XML, 2,
            "end tag </fmiModelDescription> without a start tag");
    refused("<fmiModelDescription fmiVersion='3.0'/>", SSX_MD_NOT_FMI2, 1, NULL);
}

/* Texts with references are named decoded, once (an '&' in a decoded text is plain). */
static void names_decoded_texts(void)
{
    const char *twice = "<fmiModelDescription fmiVersion='2.0'><ModelVariables>"
                        "<ScalarVariable name='a&amp;&#10;b' valueReference='0'><Real/>"
                        "</ScalarVariable><ScalarVariable name='a&amp;&#10;b' "
                        "valueReference='1'><Real/></ScalarVariable></ModelVariables>"
                        "</fmiModelDescription>";
    ssx_md *md = ssx_md_read(twice, strlen(twice));
    /* a name declared twice is read, counted, and found as its first variable */
    CHECK(md->error.problem == SSX_MD_OK);
    CHECK(md->variable_count == 2 && md->duplicate_count == 1);
    CHECK(ssx_md_find(md, "a&\nb") == 0);
    CHECK(strcmp(md->strings + md->name[1], "a&\nb") == 0);
    ssx_md_free(md);
    const char *dependency = "<fmiModelDescription fmiVersion='2.0'><ModelVariables>"
                             "<ScalarVariable name='y' valueReference='0' causality='output'>"
                             "<Real/></ScalarVariable></ModelVariables><ModelStructure>"
                             "<Outputs><Unknown index='1' dependencies='1 &amp;x'/></Outputs>"
                             "</ModelStructure></fmiModelDescription>";
    md = ssx_md_read(dependency, strlen(dependency));
    CHECK(md->error.problem == SSX_MD_BAD_INDEX);
    CHECK(strcmp(md->error.text, "&x") == 0 && md->error.count == 1);
    ssx_md_free(md);
}

static void refuses_hostile_shapes(void)
{
    /* a million nested elements: a stack entry each up to the limit, never recursion */
    size_t depth = 1000000;
    char *deep = malloc(3 * depth + 1);
    CHECK(deep != NULL);
    for (size_t i = 0; i < depth; ++i) {
        memcpy(deep + 3 * i, "<a>", 3);
    }
    deep[3 * depth] = '\0';
    refused(deep, SSX_MD_NOT_XML, 1, "elements nested deeper than 10000");
    /* thousands of attributes on one element: refused before the quadratic duplicate check */
    size_t count = 5000;
    char *wide = malloc(16 * count + 64);
    CHECK(wide != NULL);
    size_t n = (size_t)sprintf(wide, "<a");
    for (size_t i = 0; i < count; ++i) {
        n += (size_t)sprintf(wide + n, " a%zu='1'", i);
    }
    strcpy(wide + n, "/>");
    refused(wide, SSX_MD_NOT_XML, 1, "more than 1000 attributes in <a>");
    free(deep);
    free(wide);
}

/* xorshift: the same mutations on every run */
static uint32_t next_random(uint32_t *state)
{
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return *state = x;
}

static void survives_mutations(const char *document)
{
    static const char SPECIAL[] = "<>&;#x\"'/=!?-[]\n\t\x80\xC3\xFF\0";
    size_t size = strlen(document);
    char *mutant = malloc(2 * size);
    CHECK(mutant != NULL);
    uint32_t state = 2463534242u;
    size_t refused_count = 0;
    for (int round = 0; round < 40000; ++round) {
        size_t n = size;
        memcpy(mutant, document, size);
        int edits = 1 + (int)(next_random(&state) % 3);
        for (int e = 0; e < edits && n > 0; ++e) {
            size_t at = next_random(&state) % n;
            size_t span = 1 + next_random(&state) % 16;
            if (span > n - at) {
                span = n - at;
            }
            switch (next_random(&state) % 5) {
            case 0: /* one byte replaced by a character XML cares about */
                mutant[at] = SPECIAL[next_random(&state) % (sizeof SPECIAL - 1)];
                break;
            case 1: /* a random byte */
                mutant[at] = (char)(next_random(&state) & 0xFF);
                break;
            case 2: /* a span removed */
                memmove(mutant + at, mutant + at + span, n - at - span);
                n -= span;
                break;
            case 3: /* a span repeated */
                if (n + span <= 2 * size) {
                    memmove(mutant + at + span, mutant + at, n - at);
                    n += span;
                }
                break;
            default: /* cut short */
                n = at;
            }
        }
        /* an exact-size copy, so AddressSanitizer sees any read past the end */
        char *exact = malloc(n > 0 ? n : 1);
        CHECK(exact != NULL);
        memcpy(exact, mutant, n);
        ssx_md *md = ssx_md_read(exact, n);
        CHECK(md != NULL);
        if (md->error.problem == SSX_MD_NOT_XML) {
            CHECK(md->error.detail[0] != '\0' && md->error.line >= 1);
        }
        if (md->error.problem != SSX_MD_OK) {
            ++refused_count;
        } else {
            /* every text the arrays point to is there */
            CHECK(ssx_md_join(md, md->name, md->variable_count, NULL, 0) < 2 * size);
            size_t repeated = 0; /* every name is found, as its first variable */
            for (size_t i = 0; i < md->variable_count; ++i) {
                int64_t first = ssx_md_find(md, text(md, md->name[i]));
                CHECK(first >= 0 && first <= (int64_t)i);
                CHECK(strcmp(text(md, md->name[first]), text(md, md->name[i])) == 0);
                repeated += first < (int64_t)i;
            }
            CHECK(repeated == md->duplicate_count);
        }
        ssx_md_free(md);
        free(exact);
    }
    CHECK(refused_count > 10000 && refused_count < 40000); /* both outcomes were exercised */
    free(mutant);
}

int main(void)
{
    reads_a_document();
    reads_fmi1_in_fmi2_words();
    names_what_is_malformed();
    names_decoded_texts();
    refuses_hostile_shapes();
    survives_mutations(DOCUMENT);
    survives_mutations(DOCUMENT_FMI1);
    return 0;
}
