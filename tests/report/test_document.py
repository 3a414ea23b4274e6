"""report.document: one list of blocks as Markdown and as HTML."""

import os
import tempfile
import unittest

import report_path  # noqa: F401  (compare/ on sys.path)
from report.document import Document, write_documents


def sample():
    doc = Document("Twin comparison: <cavity>")
    doc.heading("Distances")
    doc.heading("Walls", 3)
    doc.paragraph("L2 < noise & more")
    doc.bullets([])  # nothing to list: no block
    doc.bullets(["one", 2])
    doc.table(["quantity", "a|b"], [["T L2", "0.1 ± 0.01"], ["multi\nline", 3]])
    doc.figure("fields.png", "Bin-averaged temperature")
    return doc


class Markdown(unittest.TestCase):
    def test_blocks_in_order(self):
        self.assertEqual(sample().markdown(), "\n".join([
            "# Twin comparison: <cavity>", "",
            "## Distances", "",
            "### Walls", "",
            "L2 < noise & more", "",
            "- one", "- 2", "",
            "| quantity | a\\|b |", "|---|---|",
            "| T L2 | 0.1 ± 0.01 |",
            "| multi line | 3 |", "",
            "![fields.png](fields.png)", "", "*Bin-averaged temperature*", ""]))

    def test_empty_bullets_leave_no_block(self):
        doc = Document("t")
        doc.bullets([])
        self.assertEqual(doc.blocks, [])


class Html(unittest.TestCase):
    def test_escaped_and_structured(self):
        page = sample().html()
        self.assertTrue(page.startswith("<!DOCTYPE html>"))
        self.assertTrue(page.endswith("</body></html>"))
        self.assertIn("<title>Twin comparison: &lt;cavity&gt;</title>", page)
        self.assertIn("<h1>Twin comparison: &lt;cavity&gt;</h1>", page)
        self.assertIn("<h2>Distances</h2>", page)
        self.assertIn("<h3>Walls</h3>", page)
        self.assertIn("<p>L2 &lt; noise &amp; more</p>", page)
        self.assertIn("<ul><li>one</li><li>2</li></ul>", page)
        self.assertIn("<tr><th>quantity</th><th>a|b</th></tr>", page)
        self.assertIn("<tr><td>multi\nline</td><td>3</td></tr>", page)
        self.assertIn('<figure><img src="fields.png" alt="fields.png">'
                      "<figcaption>Bin-averaged temperature</figcaption></figure>", page)


class Writing(unittest.TestCase):
    def test_both_files_end_with_a_newline(self):
        folder = tempfile.mkdtemp()
        doc = sample()
        write_documents(doc, folder)
        with open(os.path.join(folder, "report.md"), encoding="utf-8") as f:
            self.assertEqual(f.read(), doc.markdown())  # markdown() already ends with ""
        with open(os.path.join(folder, "report.html"), encoding="utf-8") as f:
            self.assertEqual(f.read(), doc.html() + "\n")


if __name__ == "__main__":
    unittest.main()
