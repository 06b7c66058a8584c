-- Drives Neovim's built-in LSP client (0.7 or newer) against tmcl-lsp, headless: open a file
-- with a mistake, wait for its diagnostic, hover on a parameter number, fix the mistake with an
-- incremental edit and see the diagnostics clear, jump to a label's definition, ask for semantic
-- tokens and inlay hints, format the file; then open a test file (*.tmctest) with the shipped
-- filetype detection and see the server check it too.
-- Run by nvim_test.sh; TMCL_LSP, TMC_FILE, TMCTEST_FILE and TMCL_FTDETECT come from the environment.
local ok, err = pcall(function()
  local file = os.getenv('TMC_FILE')
  local id = vim.lsp.start_client({
    cmd = { os.getenv('TMCL_LSP'), '--stdio' },
    root_dir = vim.fn.fnamemodify(file, ':h'),
    init_options = { target = 'usb-2-sd' },
  })
  assert(id, 'tmcl-lsp did not start')
  vim.cmd('edit ' .. file)
  vim.bo.filetype = 'tmcl' -- Neovim 0.7 does not know .tmc; the language id is the filetype
  vim.lsp.buf_attach_client(0, id)
  assert(vim.wait(10000, function() return #vim.diagnostic.get(0) > 0 end, 50), 'no diagnostics arrived')
  local d = vim.diagnostic.get(0)[1]
  assert(d.message == "use of undefined symbol 'Lop'" and d.lnum == 4 and d.col == 5,
    'diagnostic: ' .. vim.inspect(d))
  local uri = vim.uri_from_bufnr(0)
  local r = vim.lsp.buf_request_sync(0, 'textDocument/hover', { textDocument = { uri = uri }, position = { line = 2, character = 4 } }, 5000)
  local hover = r[id].result.contents.value
  assert(hover == '4: Maximum positioning speed, 0…16777215 pps, RW, default 51200 pps (usb-2-sd)', 'hover: ' .. hover)
  vim.api.nvim_buf_set_text(0, 4, 6, 4, 6, { 'o' }) -- JA Lop -> JA Loop
  assert(vim.wait(10000, function() return #vim.diagnostic.get(0) == 0 end, 50),
    'diagnostics not cleared: ' .. vim.inspect(vim.diagnostic.get(0)))
  r = vim.lsp.buf_request_sync(0, 'textDocument/definition', { textDocument = { uri = uri }, position = { line = 4, character = 6 } }, 5000)
  assert(r[id].result.range.start.line == 1, 'definition: ' .. vim.inspect(r[id].result))
  -- Neovim 0.7 neither shows semantic tokens (0.9) nor inlay hints (0.10), but its client sends
  -- the requests: check what an editor that shows them would get.
  r = vim.lsp.buf_request_sync(0, 'textDocument/semanticTokens/full', { textDocument = { uri = uri } }, 5000)
  local data = r[id].result.data
  assert(table.concat({ unpack(data, 1, 10) }, ',') == '0,0,5,3,3,0,8,4,4,0', 'semantic tokens: ' .. vim.inspect(data))
  r = vim.lsp.buf_request_sync(0, 'textDocument/inlayHint', { textDocument = { uri = uri },
    range = { start = { line = 0, character = 0 }, ['end'] = { line = 5, character = 0 } } }, 5000)
  local hint = r[id].result[1]
  assert(#r[id].result == 1 and hint.label == ': Maximum positioning speed' and hint.position.line == 2 and hint.position.character == 5,
    'inlay hints: ' .. vim.inspect(r[id].result))
  r = vim.lsp.buf_request_sync(0, 'textDocument/formatting', { textDocument = { uri = uri }, options = { tabSize = 2, insertSpaces = true } }, 5000)
  vim.lsp.util.apply_text_edits(r[id].result, 0, 'utf-16')
  local lines = vim.api.nvim_buf_get_lines(0, 0, -1, false)
  assert(table.concat(lines, '\n') == 'Speed = 1000\nLoop:\n  SAP 4, 0, Speed\n  MVP ABS, 0, 100\n  JA Loop',
    'formatted: ' .. vim.inspect(lines))
  -- A test file: the shipped filetype detection names it tmcltest, the server attaches to that
  -- filetype as docs/editors.md sets it up, and its diagnostics arrive.
  vim.cmd('source ' .. os.getenv('TMCL_FTDETECT'))
  vim.api.nvim_create_autocmd('FileType', {
    pattern = { 'tmcl', 'tmcltest' },
    callback = function(args) vim.lsp.buf_attach_client(args.buf, id) end,
  })
  vim.cmd('edit ' .. os.getenv('TMCTEST_FILE'))
  assert(vim.bo.filetype == 'tmcltest', 'a .tmctest buffer has the filetype ' .. vim.inspect(vim.bo.filetype))
  assert(vim.lsp.buf_is_attached(0, id), 'the server is not attached to the .tmctest buffer')
  assert(vim.wait(10000, function() return #vim.diagnostic.get(0) > 0 end, 50), 'no diagnostics arrived for the test file')
  d = vim.diagnostic.get(0)[1]
  assert(d.message == "no register, label or constant named 'Tpo'; did you mean 'Top'?" and d.lnum == 2 and d.col == 19,
    'test file diagnostic: ' .. vim.inspect(d))
end)
if ok then
  io.stdout:write('neovim: diagnostics, hover, incremental change, definition, semantic tokens, inlay hints, formatting and a test file all passed\n')
  vim.cmd('qall!')
else
  io.stderr:write('FAIL: ' .. tostring(err) .. '\n')
  vim.cmd('cquit 1')
end
