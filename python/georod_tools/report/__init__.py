"""What runs leave behind, shared by the commands and studies: figures (:mod:`.figures`, with
unit-bearing labels from :mod:`.labels`), tables and CSV/markdown writers (:mod:`.tables`), the
numbers of cases as CSV and JSON lines (:mod:`.case_files`), run records and output-folder rules
(:mod:`.records`), and animations (:mod:`.animation`)."""
