"""The report document: one list of blocks rendered both as Markdown and as HTML."""

import html
import os


class Document:
    def __init__(self, title):
        self.title = title
        self.blocks = []

    def heading(self, text, level=2):
        self.blocks.append(("heading", level, text))

    def paragraph(self, text):
        self.blocks.append(("paragraph", text))

    def bullets(self, items):
        if items:
            self.blocks.append(("bullets", list(items)))

    def table(self, header, rows):
        self.blocks.append(("table", list(header), [list(r) for r in rows]))

    def figure(self, file_name, caption):
        self.blocks.append(("figure", file_name, caption))

    def markdown(self):
        def cell(text):
            return str(text).replace("|", "\\|").replace("\n", " ")

        out = [f"# {self.title}", ""]
        for block in self.blocks:
            kind = block[0]
            if kind == "heading":
                out += ["#" * block[1] + " " + block[2], ""]
            elif kind == "paragraph":
                out += [block[1], ""]
            elif kind == "bullets":
                out += [f"- {item}" for item in block[1]] + [""]
            elif kind == "table":
                out.append("| " + " | ".join(cell(h) for h in block[1]) + " |")
                out.append("|" + "---|" * len(block[1]))
                out += ["| " + " | ".join(cell(c) for c in row) + " |" for row in block[2]]
                out.append("")
            elif kind == "figure":
                out += [f"![{block[1]}]({block[1]})", "", f"*{block[2]}*", ""]
        return "\n".join(out)

    def html(self):
        e = html.escape
        out = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
               f"<title>{e(self.title)}</title>",
               "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;"
               "padding:0 1em;line-height:1.45}table{border-collapse:collapse;margin:0.5em 0 1em}"
               "th,td{border:1px solid #bbb;padding:0.25em 0.6em;text-align:left}"
               "th{background:#eee}img{max-width:100%}figure{margin:1em 0 2em}"
               "figcaption{font-size:0.92em;color:#333}</style></head><body>",
               f"<h1>{e(self.title)}</h1>"]
        for block in self.blocks:
            kind = block[0]
            if kind == "heading":
                out.append(f"<h{block[1]}>{e(block[2])}</h{block[1]}>")
            elif kind == "paragraph":
                out.append(f"<p>{e(block[1])}</p>")
            elif kind == "bullets":
                out.append("<ul>" + "".join(f"<li>{e(str(i))}</li>" for i in block[1]) + "</ul>")
            elif kind == "table":
                out.append("<table><thead><tr>" + "".join(f"<th>{e(str(h))}</th>" for h in block[1])
                           + "</tr></thead><tbody>")
                for row in block[2]:
                    out.append("<tr>" + "".join(f"<td>{e(str(c))}</td>" for c in row) + "</tr>")
                out.append("</tbody></table>")
            elif kind == "figure":
                out.append(f"<figure><img src=\"{e(block[1])}\" alt=\"{e(block[1])}\">"
                           f"<figcaption>{e(block[2])}</figcaption></figure>")
        out.append("</body></html>")
        return "\n".join(out)


def write_atomically(path, write):
    """Calls write(temporary_path), then renames it over path: no incomplete file ever sits
    under path (disk full, a kill); the temporary file is removed on failure."""
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise


def write_text(path, text):
    def write(tmp):
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text if text.endswith("\n") else text + "\n")
    write_atomically(path, write)


def write_documents(doc, out_dir):
    write_text(os.path.join(out_dir, "report.md"), doc.markdown())
    write_text(os.path.join(out_dir, "report.html"), doc.html())
